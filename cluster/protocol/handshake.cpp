#include "cluster/protocol/handshake.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>

#include "cluster/protocol/byte_io.h"

namespace zenith::cluster {
namespace {

void strip_one_newline(std::vector<std::uint8_t>& bytes) {
  if (!bytes.empty() && bytes.back() == '\n') {
    bytes.pop_back();
    if (!bytes.empty() && bytes.back() == '\r') bytes.pop_back();
  }
}

std::vector<std::uint8_t> mac_input(const char* label, std::string_view cluster_name, std::string_view node_name,
                                    const Nonce& first, const Nonce& second) {
  std::vector<std::uint8_t> out;
  ByteWriter w(out);
  w.string(label, kMaxNameBytes, "MAC label");
  w.string(cluster_name, kMaxNameBytes, "cluster name");
  w.string(node_name, kMaxNameBytes, "node name");
  w.bytes(first);
  w.bytes(second);
  return out;
}

/// The MAC labels of each role: distinct, so no MAC serves another role or direction.
const char* peer_label(PeerRole role) { return role == PeerRole::standby ? "zenith standby v1" : "zenith node v1"; }
const char* master_label(PeerRole role) {
  return role == PeerRole::standby ? "zenith master to standby v1" : "zenith master v1";
}

}  // namespace

SharedSecret::SharedSecret(std::vector<std::uint8_t> bytes, std::string source)
    : bytes_(std::move(bytes)), source_(std::move(source)) {
  if (bytes_.size() < kMinSecretBytes)
    throw std::invalid_argument("shared secret from " + source_ + ": " + std::to_string(bytes_.size()) +
                                " bytes, at least " + std::to_string(kMinSecretBytes) + " required");
}

SharedSecret::~SharedSecret() {
  if (!bytes_.empty()) OPENSSL_cleanse(bytes_.data(), bytes_.size());
}

SharedSecret load_shared_secret(const std::optional<std::filesystem::path>& file, const char* env_var) {
  if (file) {
    const std::string name = file->string();
    struct stat st {};
    if (::stat(name.c_str(), &st) != 0)
      throw std::runtime_error("shared secret file " + name + ": " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw std::runtime_error("shared secret file " + name + ": not a regular file");
    if ((st.st_mode & 0077) != 0) {
      std::ostringstream mode;
      mode << std::oct << (st.st_mode & 0777);
      throw std::runtime_error("shared secret file " + name + ": mode 0" + mode.str() +
                               " lets group or others access it; run chmod 600 " + name);
    }
    if (static_cast<std::uintmax_t>(st.st_size) > kMaxSecretBytes + 2)
      throw std::runtime_error("shared secret file " + name + ": " + std::to_string(st.st_size) + " bytes, at most " +
                               std::to_string(kMaxSecretBytes) + " allowed");
    std::ifstream in(*file, std::ios::binary);
    if (!in) throw std::runtime_error("shared secret file " + name + ": cannot open for reading");
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    strip_one_newline(bytes);
    if (bytes.size() < kMinSecretBytes)
      throw std::runtime_error("shared secret file " + name + ": " + std::to_string(bytes.size()) +
                               " bytes, at least " + std::to_string(kMinSecretBytes) + " required");
    return SharedSecret(std::move(bytes), "file " + name);
  }
  const char* value = std::getenv(env_var);
  if (value == nullptr)
    throw std::runtime_error(std::string("no shared secret: environment variable ") + env_var +
                             " is not set and no secret file was given");
  std::vector<std::uint8_t> bytes(value, value + std::strlen(value));
  if (bytes.empty())
    throw std::runtime_error(std::string("shared secret: environment variable ") + env_var + " is empty");
  strip_one_newline(bytes);
  if (bytes.size() < kMinSecretBytes)
    throw std::runtime_error(std::string("shared secret: environment variable ") + env_var + " holds " +
                             std::to_string(bytes.size()) + " bytes, at least " + std::to_string(kMinSecretBytes) +
                             " required");
  if (bytes.size() > kMaxSecretBytes)
    throw std::runtime_error(std::string("shared secret: environment variable ") + env_var + " holds " +
                             std::to_string(bytes.size()) + " bytes, at most " + std::to_string(kMaxSecretBytes) +
                             " allowed");
  return SharedSecret(std::move(bytes), std::string("environment variable ") + env_var);
}

Digest hmac_sha256(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message) {
  Digest out{};
  unsigned int length = 0;
  // HMAC() accepts a null key pointer only with length 0; give it a valid one.
  static const std::uint8_t kEmpty = 0;
  const std::uint8_t* key_data = key.empty() ? &kEmpty : key.data();
  const unsigned char* message_data = message.empty() ? &kEmpty : message.data();
  if (HMAC(EVP_sha256(), key_data, static_cast<int>(key.size()), message_data, message.size(), out.data(), &length) ==
          nullptr ||
      length != out.size())
    throw std::runtime_error("HMAC-SHA256 failed (OpenSSL)");
  return out;
}

bool digests_equal(const Digest& a, const Digest& b) { return CRYPTO_memcmp(a.data(), b.data(), a.size()) == 0; }

Nonce random_nonce() {
  Nonce n{};
  if (RAND_bytes(n.data(), static_cast<int>(n.size())) != 1)
    throw std::runtime_error("RAND_bytes failed: no randomness for the handshake nonce");
  return n;
}

std::vector<std::uint8_t> node_mac_input(std::string_view cluster_name, std::string_view node_name,
                                         const Nonce& master_nonce, const Nonce& node_nonce, PeerRole role) {
  return mac_input(peer_label(role), cluster_name, node_name, master_nonce, node_nonce);
}
std::vector<std::uint8_t> master_mac_input(std::string_view cluster_name, std::string_view node_name,
                                           const Nonce& node_nonce, const Nonce& master_nonce, PeerRole role) {
  return mac_input(master_label(role), cluster_name, node_name, node_nonce, master_nonce);
}
Digest node_mac(const SharedSecret& secret, std::string_view cluster_name, std::string_view node_name,
                const Nonce& master_nonce, const Nonce& node_nonce, PeerRole role) {
  return hmac_sha256(secret.bytes(), node_mac_input(cluster_name, node_name, master_nonce, node_nonce, role));
}
Digest master_mac(const SharedSecret& secret, std::string_view cluster_name, std::string_view node_name,
                  const Nonce& node_nonce, const Nonce& master_nonce, PeerRole role) {
  return hmac_sha256(secret.bytes(), master_mac_input(cluster_name, node_name, node_nonce, master_nonce, role));
}
Digest datagram_key(const SharedSecret& secret, std::string_view cluster_name, std::string_view node_name,
                    const Nonce& master_nonce, const Nonce& node_nonce) {
  return hmac_sha256(secret.bytes(),
                     mac_input("zenith datagrams v1", cluster_name, node_name, master_nonce, node_nonce));
}

// ---- node ------------------------------------------------------------------------

NodeHandshake::NodeHandshake(SharedSecret secret, std::string cluster_name, std::string node_name, PeerRole role,
                             std::uint64_t instance_id)
    : secret_(std::move(secret)),
      cluster_name_(std::move(cluster_name)),
      node_name_(std::move(node_name)),
      role_(role),
      instance_id_(instance_id != 0 ? instance_id : random_instance_id()) {}

std::uint64_t random_instance_id() {
  for (;;) {
    const Nonce bytes = random_nonce();
    std::uint64_t id = 0;
    for (int i = 0; i < 8; ++i) id = (id << 8) | bytes[static_cast<std::size_t>(i)];
    if (id != 0) return id;
  }
}

Hello NodeHandshake::start() {
  if (state_ != State::initial) throw std::logic_error("NodeHandshake::start called twice");
  node_nonce_ = random_nonce();
  state_ = State::hello_sent;
  return Hello{kProtocolVersion, cluster_name_, node_name_, node_nonce_, role_, instance_id_};
}

Authenticate NodeHandshake::on_challenge(const Challenge& challenge) {
  if (state_ != State::hello_sent)
    throw HandshakeError(RejectReason::protocol_error, "handshake: unexpected Challenge from the master");
  master_nonce_ = challenge.master_nonce;
  state_ = State::authenticate_sent;
  return Authenticate{node_mac(secret_, cluster_name_, node_name_, master_nonce_, node_nonce_, role_)};
}

void NodeHandshake::on_welcome(const Welcome& welcome) {
  if (state_ != State::authenticate_sent)
    throw HandshakeError(RejectReason::protocol_error, "handshake: unexpected Welcome from the master");
  const Digest expected = master_mac(secret_, cluster_name_, node_name_, node_nonce_, master_nonce_, role_);
  if (!digests_equal(expected, welcome.master_mac))
    throw HandshakeError(
        RejectReason::authentication_failed,
        "handshake: the master's MAC is wrong (it does not hold the shared secret from " + secret_.source() + ")");
  state_ = State::done;
}

Digest NodeHandshake::datagram_key() const {
  if (state_ != State::done) throw std::logic_error("NodeHandshake::datagram_key before the master was verified");
  return cluster::datagram_key(secret_, cluster_name_, node_name_, master_nonce_, node_nonce_);
}

// ---- master ----------------------------------------------------------------------

MasterHandshake::MasterHandshake(SharedSecret secret, std::string cluster_name)
    : secret_(std::move(secret)), cluster_name_(std::move(cluster_name)) {}

Challenge MasterHandshake::on_hello(const Hello& hello) {
  if (state_ != State::initial) throw HandshakeError(RejectReason::protocol_error, "handshake: second Hello");
  if (hello.protocol_version != kProtocolVersion)
    throw HandshakeError(RejectReason::unsupported_version, std::string("handshake: ") + to_string(hello.role) + " '" +
                                                                hello.node_name + "' speaks protocol version " +
                                                                std::to_string(hello.protocol_version) +
                                                                ", this master " + std::to_string(kProtocolVersion));
  if (hello.cluster_name != cluster_name_)
    throw HandshakeError(RejectReason::wrong_cluster, std::string("handshake: ") + to_string(hello.role) + " '" +
                                                          hello.node_name + "' wants cluster '" + hello.cluster_name +
                                                          "', this is '" + cluster_name_ + "'");
  node_name_ = hello.node_name;
  role_ = hello.role;
  node_nonce_ = hello.node_nonce;
  master_nonce_ = random_nonce();
  state_ = State::challenge_sent;
  return Challenge{master_nonce_};
}

void MasterHandshake::on_authenticate(const Authenticate& authenticate) {
  if (state_ != State::challenge_sent)
    throw HandshakeError(RejectReason::protocol_error, "handshake: unexpected Authenticate");
  const Digest expected = node_mac(secret_, cluster_name_, node_name_, master_nonce_, node_nonce_, role_);
  if (!digests_equal(expected, authenticate.node_mac))
    throw HandshakeError(RejectReason::authentication_failed, std::string("handshake: ") + to_string(role_) + " '" +
                                                                  node_name_ +
                                                                  "' failed authentication (wrong shared secret)");
  state_ = State::done;
}

Welcome MasterHandshake::welcome(std::uint32_t node_id, std::uint64_t current_frame,
                                 std::uint32_t heartbeat_interval_ms, std::uint32_t barrier_timeout_ms,
                                 std::uint64_t master_time_ns) const {
  if (state_ != State::done) throw std::logic_error("MasterHandshake::welcome before the node authenticated");
  return Welcome{node_id,
                 master_mac(secret_, cluster_name_, node_name_, node_nonce_, master_nonce_, role_),
                 current_frame,
                 heartbeat_interval_ms,
                 barrier_timeout_ms,
                 master_time_ns};
}

Digest MasterHandshake::datagram_key() const {
  if (state_ != State::done) throw std::logic_error("MasterHandshake::datagram_key before the node authenticated");
  return cluster::datagram_key(secret_, cluster_name_, node_name_, master_nonce_, node_nonce_);
}

}  // namespace zenith::cluster
