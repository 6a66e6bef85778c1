#pragma once
// Mutual authentication of a node and the master with the cluster's shared
// secret (HMAC-SHA256 challenge–response; docs/protocol.md, "Handshake").
//
//   node                                   master
//   Hello{version, cluster, node, Nn}  ──►
//                                     ◄──  Challenge{Nm}
//   Authenticate{node_mac}             ──►  verifies node_mac
//                                     ◄──  Welcome{id, master_mac, …}  (or Reject, then close)
//   verifies master_mac (else Goodbye, close)
//
//   node_mac   = HMAC(secret, str("zenith node v1")   ‖ str(cluster) ‖ str(node) ‖ Nm ‖ Nn)
//   master_mac = HMAC(secret, str("zenith master v1") ‖ str(cluster) ‖ str(node) ‖ Nn ‖ Nm)
//
// where str(s) is a big-endian u16 byte count followed by the bytes. A standby
// master (Hello.role = standby) uses the labels "zenith standby v1" and
// "zenith master to standby v1" instead, so a MAC of one role never serves
// the other and the role in the Hello is authenticated with the secret. Both
// nonces are fresh 32-byte RAND_bytes values, so neither MAC can be replayed,
// and the different labels keep one side's MAC from ever serving as the other's.
// The secret never travels.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cluster/protocol/messages.h"

namespace zenith::cluster {

/// Minimum length of a shared secret in bytes.
inline constexpr std::size_t kMinSecretBytes = 16;
/// Maximum length of a shared secret file in bytes (it is a key, not a document).
inline constexpr std::size_t kMaxSecretBytes = 4096;

/// The cluster's shared secret. Its bytes are wiped when it is destroyed.
class SharedSecret {
 public:
  /// Throws std::invalid_argument when shorter than kMinSecretBytes.
  SharedSecret(std::vector<std::uint8_t> bytes, std::string source);
  SharedSecret(const SharedSecret&) = default;
  SharedSecret& operator=(const SharedSecret&) = default;
  ~SharedSecret();

  std::span<const std::uint8_t> bytes() const { return bytes_; }
  /// Where it came from ("file /etc/zenith/secret", "environment variable ZENITH_CLUSTER_SECRET"), for logs.
  const std::string& source() const { return source_; }

 private:
  std::vector<std::uint8_t> bytes_;
  std::string source_;
};

/// Reads the shared secret from `file` when given, otherwise from the
/// environment variable `env_var`. There is deliberately no way to pass it on
/// the command line (visible in `ps` and shell history).
///
/// File: must exist, be a regular file and grant no permission to group or
/// others (mode & 0077 == 0, as OpenSSH requires of private keys; fix with
/// `chmod 600`); one trailing "\n" or "\r\n" is stripped. Either source: at
/// least kMinSecretBytes bytes after stripping. Throws std::runtime_error
/// naming the file or the variable.
SharedSecret load_shared_secret(const std::optional<std::filesystem::path>& file,
                                const char* env_var = "ZENITH_CLUSTER_SECRET");

/// HMAC-SHA256 (RFC 2104) through OpenSSL.
Digest hmac_sha256(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message);
/// Constant-time comparison (CRYPTO_memcmp).
bool digests_equal(const Digest& a, const Digest& b);
/// 32 bytes from RAND_bytes; throws std::runtime_error if the CSPRNG fails.
Nonce random_nonce();

/// The exact bytes the MACs cover (exposed for tests and docs); the label depends on the connecting peer's role.
std::vector<std::uint8_t> node_mac_input(std::string_view cluster_name, std::string_view node_name,
                                         const Nonce& master_nonce, const Nonce& node_nonce,
                                         PeerRole role = PeerRole::node);
std::vector<std::uint8_t> master_mac_input(std::string_view cluster_name, std::string_view node_name,
                                           const Nonce& node_nonce, const Nonce& master_nonce,
                                           PeerRole role = PeerRole::node);
/// The connecting peer's proof (a node's, or a standby's with `role` standby).
Digest node_mac(const SharedSecret& secret, std::string_view cluster_name, std::string_view node_name,
                const Nonce& master_nonce, const Nonce& node_nonce, PeerRole role = PeerRole::node);
/// The key of the session's datagrams (cluster/protocol/datagram.h):
///   HMAC(secret, str("zenith datagrams v1") ‖ str(cluster) ‖ str(node) ‖ Nm ‖ Nn)
/// Both sides derive it once the handshake is done; it never travels, and a
/// new connection (new nonces) has a new key, so no datagram of an earlier
/// session is ever accepted.
Digest datagram_key(const SharedSecret& secret, std::string_view cluster_name, std::string_view node_name,
                    const Nonce& master_nonce, const Nonce& node_nonce);
/// The master's proof to a peer of `role`.
Digest master_mac(const SharedSecret& secret, std::string_view cluster_name, std::string_view node_name,
                  const Nonce& node_nonce, const Nonce& master_nonce, PeerRole role = PeerRole::node);

/// The handshake failed: the connection is refused (master: send Reject with
/// `reason()`, then close; node: send Goodbye, then close) and logged.
class HandshakeError : public std::runtime_error {
 public:
  HandshakeError(RejectReason reason, const std::string& detail) : std::runtime_error(detail), reason_(reason) {}
  RejectReason reason() const noexcept { return reason_; }

 private:
  RejectReason reason_;
};

/// The connecting side (a node, or a standby master with `role` standby):
/// start() → Hello; on Challenge → Authenticate; on Welcome → verify the
/// master. Not thread-safe; one per connection.
class NodeHandshake {
 public:
  /// `instance_id`: this process's (Hello.instance_id; random_instance_id() once per process).
  NodeHandshake(SharedSecret secret, std::string cluster_name, std::string node_name, PeerRole role = PeerRole::node,
                std::uint64_t instance_id = 0);
  Hello start();
  Authenticate on_challenge(const Challenge& challenge);
  /// Throws HandshakeError(authentication_failed) when the master's MAC is
  /// wrong (it does not know the secret) or when called out of order.
  void on_welcome(const Welcome& welcome);
  bool authenticated() const { return state_ == State::done; }
  /// datagram_key() of this session; only once authenticated (else std::logic_error).
  Digest datagram_key() const;

 private:
  enum class State { initial, hello_sent, authenticate_sent, done };
  SharedSecret secret_;
  std::string cluster_name_, node_name_;
  PeerRole role_;
  std::uint64_t instance_id_;
  Nonce node_nonce_{}, master_nonce_{};
  State state_ = State::initial;
};

/// A fresh random Hello.instance_id (RAND_bytes), never 0.
std::uint64_t random_instance_id();

/// The master's side for one connection: on Hello → Challenge; on
/// Authenticate → verify; then welcome() builds the Welcome carrying the
/// master's own proof.
class MasterHandshake {
 public:
  MasterHandshake(SharedSecret secret, std::string cluster_name);
  /// Throws HandshakeError(wrong_cluster / unsupported_version) or on a second Hello.
  Challenge on_hello(const Hello& hello);
  /// Throws HandshakeError(authentication_failed) when the node's MAC is wrong.
  void on_authenticate(const Authenticate& authenticate);
  /// Only after on_authenticate succeeded (else std::logic_error).
  Welcome welcome(std::uint32_t node_id, std::uint64_t current_frame, std::uint32_t heartbeat_interval_ms,
                  std::uint32_t barrier_timeout_ms, std::uint64_t master_time_ns = 0) const;
  bool authenticated() const { return state_ == State::done; }
  /// datagram_key() of this session; only once authenticated (else std::logic_error).
  Digest datagram_key() const;
  /// The node's name from its Hello (empty before).
  const std::string& node_name() const { return node_name_; }
  /// The peer's role from its Hello (node before).
  PeerRole role() const { return role_; }

 private:
  enum class State { initial, challenge_sent, done };
  SharedSecret secret_;
  std::string cluster_name_, node_name_;
  PeerRole role_ = PeerRole::node;
  Nonce node_nonce_{}, master_nonce_{};
  State state_ = State::initial;
};

}  // namespace zenith::cluster
