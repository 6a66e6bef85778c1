#include "cluster/protocol/handshake.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <random>

namespace zenith::cluster {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes bytes_of(std::string_view s) { return Bytes(s.begin(), s.end()); }
SharedSecret secret_of(std::string_view s) { return SharedSecret(bytes_of(s), "test"); }

TEST(Hmac, Rfc4231TestCase1) {
  const Bytes key(20, 0x0b);
  EXPECT_EQ(to_hex(hmac_sha256(key, bytes_of("Hi There"))),
            "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7");
}

TEST(Hmac, Rfc4231TestCase2) {
  EXPECT_EQ(to_hex(hmac_sha256(bytes_of("Jefe"), bytes_of("what do ya want for nothing?"))),
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
}

TEST(Hmac, Rfc4231TestCase6KeyLongerThanABlock) {
  const Bytes key(131, 0xaa);
  EXPECT_EQ(to_hex(hmac_sha256(key, bytes_of("Test Using Larger Than Block-Size Key - Hash Key First"))),
            "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54");
}

TEST(Handshake, MacInputLayoutIsLengthPrefixed) {
  Nonce a{}, b{};
  a.fill(0xAA);
  b.fill(0xBB);
  const Bytes input = node_mac_input("c", "nd", a, b);
  Bytes expected = {0, 14};
  for (char ch : std::string("zenith node v1")) expected.push_back(static_cast<std::uint8_t>(ch));
  expected.insert(expected.end(), {0, 1, 'c', 0, 2, 'n', 'd'});
  expected.insert(expected.end(), a.begin(), a.end());
  expected.insert(expected.end(), b.begin(), b.end());
  EXPECT_EQ(input, expected);
  const Bytes m = master_mac_input("c", "nd", b, a);
  EXPECT_EQ(Bytes(m.begin(), m.begin() + 18), bytes_of(std::string("\0\x10zenith master v1", 18)));
  // Length prefixes keep ("ab","c") and ("a","bc") apart.
  EXPECT_NE(node_mac_input("ab", "c", a, b), node_mac_input("a", "bc", a, b));
}

TEST(Handshake, CorrectSecretAuthenticatesBothWays) {
  const SharedSecret secret = secret_of("correct horse battery staple");
  NodeHandshake node(secret, "dome", "node-1");
  MasterHandshake master(secret, "dome");
  const Hello hello = node.start();
  const Challenge challenge = master.on_hello(hello);
  EXPECT_NE(challenge.master_nonce, hello.node_nonce);
  const Authenticate auth = node.on_challenge(challenge);
  EXPECT_NO_THROW(master.on_authenticate(auth));
  EXPECT_TRUE(master.authenticated());
  EXPECT_EQ(master.node_name(), "node-1");
  const Welcome welcome = master.welcome(7, 1234, 250, 2000);
  EXPECT_EQ(welcome.node_id, 7u);
  EXPECT_NO_THROW(node.on_welcome(welcome));
  EXPECT_TRUE(node.authenticated());
}

TEST(Handshake, StandbyAuthenticatesWithItsOwnLabels) {
  const SharedSecret secret = secret_of("correct horse battery staple");
  NodeHandshake standby(secret, "dome", "standby@10.0.0.2:47101", PeerRole::standby);
  MasterHandshake master(secret, "dome");
  const Hello hello = standby.start();
  EXPECT_EQ(hello.role, PeerRole::standby);
  const Authenticate auth = standby.on_challenge(master.on_hello(hello));
  EXPECT_NO_THROW(master.on_authenticate(auth));
  EXPECT_EQ(master.role(), PeerRole::standby);
  EXPECT_NO_THROW(standby.on_welcome(master.welcome(3, 0, 250, 2000)));
  EXPECT_TRUE(standby.authenticated());

  Nonce a{}, b{};
  a.fill(0xAA);
  b.fill(0xBB);
  const Bytes input = node_mac_input("c", "nd", a, b, PeerRole::standby);
  EXPECT_EQ(Bytes(input.begin(), input.begin() + 19), bytes_of(std::string("\0\x11zenith standby v1", 19)));
  const Bytes m = master_mac_input("c", "nd", b, a, PeerRole::standby);
  EXPECT_EQ(Bytes(m.begin(), m.begin() + 29), bytes_of(std::string("\0\x1bzenith master to standby v1", 29)));
  EXPECT_NE(node_mac(secret, "c", "nd", a, b, PeerRole::standby), node_mac(secret, "c", "nd", a, b));
  EXPECT_NE(master_mac(secret, "c", "nd", b, a, PeerRole::standby), master_mac(secret, "c", "nd", b, a));
}

TEST(Handshake, ARoleChangedInTransitFailsAuthentication) {
  // The role is bound by the MAC labels: a node's proof does not pass as a standby's, nor the other way.
  const SharedSecret secret = secret_of("correct horse battery staple");
  NodeHandshake node(secret, "dome", "node-1");
  MasterHandshake master(secret, "dome");
  Hello hello = node.start();
  hello.role = PeerRole::standby;
  const Authenticate auth = node.on_challenge(master.on_hello(hello));
  try {
    master.on_authenticate(auth);
    FAIL() << "a node's MAC must not authenticate a standby";
  } catch (const HandshakeError& e) {
    EXPECT_EQ(e.reason(), RejectReason::authentication_failed);
    EXPECT_NE(std::string(e.what()).find("standby 'node-1' failed authentication"), std::string::npos) << e.what();
  }

  NodeHandshake standby(secret, "dome", "standby@h:1", PeerRole::standby);
  MasterHandshake master2(secret, "dome");
  Hello as_node = standby.start();
  as_node.role = PeerRole::node;
  EXPECT_THROW(master2.on_authenticate(standby.on_challenge(master2.on_hello(as_node))), HandshakeError);
}

TEST(Handshake, WrongSecretOnTheNodeIsRejectedByTheMaster) {
  NodeHandshake node(secret_of("this is not the secret"), "dome", "node-1");
  MasterHandshake master(secret_of("correct horse battery staple"), "dome");
  const Challenge challenge = master.on_hello(node.start());
  try {
    master.on_authenticate(node.on_challenge(challenge));
    FAIL() << "accepted";
  } catch (const HandshakeError& e) {
    EXPECT_EQ(e.reason(), RejectReason::authentication_failed);
    EXPECT_NE(std::string(e.what()).find("node-1"), std::string::npos);
  }
  EXPECT_FALSE(master.authenticated());
  EXPECT_THROW(master.welcome(1, 0, 250, 2000), std::logic_error);
}

TEST(Handshake, WrongSecretOnTheMasterIsDetectedByTheNode) {
  // An impostor master: it cannot check the node's MAC and welcomes anyway.
  NodeHandshake node(secret_of("correct horse battery staple"), "dome", "node-1");
  MasterHandshake impostor(secret_of("guessing the secret..."), "dome");
  const Authenticate auth = node.on_challenge(impostor.on_hello(node.start()));
  EXPECT_THROW(impostor.on_authenticate(auth), HandshakeError);
  Welcome forged{1, {}, 0, 250, 2000};
  forged.master_mac = master_mac(secret_of("guessing the secret..."), "dome", "node-1", {}, {});
  try {
    node.on_welcome(forged);
    FAIL() << "accepted";
  } catch (const HandshakeError& e) {
    EXPECT_EQ(e.reason(), RejectReason::authentication_failed);
  }
  EXPECT_FALSE(node.authenticated());
}

TEST(Handshake, ReplayedNodeMacFailsAgainstAFreshChallenge) {
  const SharedSecret secret = secret_of("correct horse battery staple");
  NodeHandshake node(secret, "dome", "node-1");
  MasterHandshake first(secret, "dome");
  const Hello hello = node.start();
  const Authenticate recorded = node.on_challenge(first.on_hello(hello));
  MasterHandshake second(secret, "dome");
  second.on_hello(hello);  // the attacker replays Hello, gets a new master nonce
  EXPECT_THROW(second.on_authenticate(recorded), HandshakeError);
}

TEST(Handshake, WrongClusterAndOutOfOrderMessages) {
  const SharedSecret secret = secret_of("correct horse battery staple");
  MasterHandshake master(secret, "dome");
  NodeHandshake node(secret, "planetarium-b", "node-1");
  try {
    master.on_hello(node.start());
    FAIL();
  } catch (const HandshakeError& e) {
    EXPECT_EQ(e.reason(), RejectReason::wrong_cluster);
  }
  NodeHandshake fresh(secret, "dome", "node-2");
  EXPECT_THROW(fresh.on_welcome(Welcome{}), HandshakeError);
  EXPECT_THROW(fresh.on_challenge(Challenge{}), HandshakeError);
  MasterHandshake m2(secret, "dome");
  EXPECT_THROW(m2.on_authenticate(Authenticate{}), HandshakeError);
}

TEST(Handshake, NoncesAreRandom) { EXPECT_NE(random_nonce(), random_nonce()); }

TEST(Handshake, ConstantTimeComparison) {
  Digest a{}, b{};
  EXPECT_TRUE(digests_equal(a, b));
  b[31] = 1;
  EXPECT_FALSE(digests_equal(a, b));
}

// ---- loading the secret ------------------------------------------------------------

class SecretFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("zenith-secret-test-" + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(dir_);
    ::unsetenv(kVar);
  }
  void TearDown() override {
    std::filesystem::remove_all(dir_);
    ::unsetenv(kVar);
  }
  std::filesystem::path write(const std::string& name, const std::string& content, mode_t mode) {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << content;
    ::chmod(path.c_str(), mode);
    return path;
  }
  static std::string message_of(const std::optional<std::filesystem::path>& file) {
    try {
      load_shared_secret(file, kVar);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  static constexpr const char* kVar = "ZENITH_TEST_CLUSTER_SECRET";
  std::filesystem::path dir_;
};

TEST_F(SecretFile, ReadsAFileAndStripsOneTrailingNewline) {
  const auto path = write("secret", "0123456789abcdef0123\n", 0600);
  const SharedSecret s = load_shared_secret(path, kVar);
  EXPECT_EQ(Bytes(s.bytes().begin(), s.bytes().end()), bytes_of("0123456789abcdef0123"));
  EXPECT_EQ(s.source(), "file " + path.string());
  const auto crlf = write("secret-crlf", "0123456789abcdef0123\r\n", 0400);
  EXPECT_EQ(load_shared_secret(crlf, kVar).bytes().size(), 20u);
}

TEST_F(SecretFile, FileTakesPrecedenceOverTheEnvironment) {
  ::setenv(kVar, "environment-secret-value", 1);
  const auto path = write("secret", "file-secret-value-123", 0600);
  EXPECT_EQ(load_shared_secret(path, kVar).source(), "file " + path.string());
}

TEST_F(SecretFile, MissingFile) {
  const std::string m = message_of(dir_ / "nope");
  EXPECT_NE(m.find("nope"), std::string::npos) << m;
  EXPECT_NE(m.find("No such file"), std::string::npos) << m;
}

TEST_F(SecretFile, GroupOrWorldAccessibleFileIsRefused) {
  for (mode_t mode : {0644, 0640, 0604, 0660}) {
    const auto path = write("secret", "0123456789abcdef0123", mode);
    const std::string m = message_of(path);
    EXPECT_NE(m.find("chmod 600"), std::string::npos) << m;
    EXPECT_NE(m.find(path.string()), std::string::npos) << m;
  }
}

TEST_F(SecretFile, TooShortFile) {
  const std::string m = message_of(write("secret", "short\n", 0600));
  EXPECT_NE(m.find("5 bytes, at least 16"), std::string::npos) << m;
}

TEST_F(SecretFile, DirectoryIsNotASecret) {
  ::chmod(dir_.c_str(), 0700);
  EXPECT_NE(message_of(dir_).find("not a regular file"), std::string::npos);
}

TEST_F(SecretFile, FromTheEnvironment) {
  ::setenv(kVar, "an environment secret!", 1);
  const SharedSecret s = load_shared_secret(std::nullopt, kVar);
  EXPECT_EQ(s.bytes().size(), 22u);
  EXPECT_EQ(s.source(), std::string("environment variable ") + kVar);
}

TEST_F(SecretFile, UnsetEmptyOrShortEnvironment) {
  std::string m = message_of(std::nullopt);
  EXPECT_NE(m.find(kVar), std::string::npos) << m;
  EXPECT_NE(m.find("not set"), std::string::npos) << m;
  ::setenv(kVar, "", 1);
  m = message_of(std::nullopt);
  EXPECT_NE(m.find("is empty"), std::string::npos) << m;
  ::setenv(kVar, "tiny", 1);
  m = message_of(std::nullopt);
  EXPECT_NE(m.find("4 bytes, at least 16"), std::string::npos) << m;
}

TEST(SharedSecret, RefusesShortSecretsBuiltInCode) {
  EXPECT_THROW(SharedSecret(Bytes(15, 1), "code"), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::cluster
