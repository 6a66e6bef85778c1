#pragma once
// One TCP connection carrying protocol frames (docs/protocol.md) on a
// Boost.Asio io_context. Every member function must be called on the thread
// running that io_context (the master and the node run one such thread and do
// all their networking there), so no locking is needed.
//
// Reading: the socket is read in pieces of at most kReadChunkBytes, fed to a
// FrameDecoder and the decoded messages handed to the message handler one by
// one. A ProtocolError closes the connection (there is no resynchronisation).
// Writing: send() queues an encoded frame; frames go out in order, one
// async_write at a time. close_after_flush() lets the queue drain first
// (Goodbye, Reject), close() drops it.
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>

#include "cluster/protocol/frame_decoder.h"
#include "cluster/protocol/messages.h"

namespace zenith::cluster {

class Connection : public std::enable_shared_from_this<Connection> {
 public:
  /// Bytes asked of the socket per read.
  static constexpr std::size_t kReadChunkBytes = 64 * 1024;

  using MessageHandler = std::function<void(Message&& message)>;
  /// Called exactly once, when the connection closes for any reason (`reason`
  /// for the log: "end of stream", "protocol error: ...", the caller's text).
  using CloseHandler = std::function<void(const std::string& reason)>;

  Connection(boost::asio::ip::tcp::socket socket, std::string peer);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  /// Starts reading. The handlers are called on the io_context's thread.
  void start(MessageHandler on_message, CloseHandler on_close);
  /// Encodes `message` and queues it (ignored once closing).
  void send(const Message& message);
  /// Queues already encoded frames (e.g. shared table chunks).
  void send_encoded(std::shared_ptr<const std::vector<std::uint8_t>> frame);
  /// Sends what is queued, then shuts sending down (the peer reads to the
  /// end, then end of stream) and closes once the peer has closed too;
  /// `reason` goes to the close handler. Nothing received from now on is
  /// handled (it is read and dropped). Closes after `grace` at the latest.
  /// Why wait for the peer: closing a socket with unread bytes in its
  /// receive buffer makes the kernel send a reset, which discards what the
  /// peer has not acknowledged yet — on a lossy link the Goodbye itself, and
  /// the node would then take the master's stop for a crash.
  void close_after_flush(const std::string& reason, std::chrono::milliseconds grace = std::chrono::milliseconds(2000));
  /// Closes now, dropping unsent frames.
  void close(const std::string& reason);

  bool is_open() const { return open_ && !closing_; }
  /// "127.0.0.1:53122" (or the name given), for logs.
  const std::string& peer() const { return peer_; }
  /// The peer's address and port (nothing once the socket is closed).
  std::optional<boost::asio::ip::tcp::endpoint> remote_endpoint() const;
  /// When bytes last arrived from the peer (for liveness).
  std::chrono::steady_clock::time_point last_received() const { return last_received_; }
  /// Until lift_payload_limit(): every payload at most `max_bytes` (a larger
  /// header closes the connection as **oversized**, naming `why`), and the
  /// socket read in pieces of kLimitedReadBytes — what a peer that has not
  /// authenticated may make this side hold (docs/cluster.md, "Threat model").
  void limit_payload(std::uint32_t max_bytes, std::string why);
  void lift_payload_limit();
  /// Bytes asked of the socket per read while the payload is limited.
  static constexpr std::size_t kLimitedReadBytes = 2048;

 private:
  void read_more();
  void write_next();
  void finish(const std::string& reason);
  /// close_after_flush with the queue empty: our end of stream, then the wait for the peer's.
  void shut_down_sending();

  boost::asio::ip::tcp::socket socket_;
  boost::asio::steady_timer grace_timer_;
  std::string peer_;
  FrameDecoder decoder_;
  std::vector<std::uint8_t> read_buffer_;
  std::deque<std::shared_ptr<const std::vector<std::uint8_t>>> queue_;
  bool writing_ = false;
  bool open_ = false;     ///< started and not finished
  bool closing_ = false;  ///< close_after_flush() called
  bool finished_ = false;
  std::string closing_reason_;
  MessageHandler on_message_;
  CloseHandler on_close_;
  std::chrono::steady_clock::time_point last_received_;
};

}  // namespace zenith::cluster
