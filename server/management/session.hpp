#pragma once
// One connection of the management endpoint: reads framed Requests continuously and hands each
// to the dispatch function; sends framed Responses in order. Owned by shared_ptr: the pending
// asynchronous operations keep it alive, so callers hold it (or a weak_ptr) only to answer.

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio.hpp>
#include <boost/asio/ssl.hpp>

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <variant>

#include "idl/management.pb.h"
#include "server/management/frame_codec.hpp"
#include "server/management/peer.hpp"

namespace netmc::management {

// How long a connection may hold the server's resources without using them.
struct SessionLimits {
  // No byte in either direction for this long: closed (a client waiting for a job's updates is
  // not idle while they come; a client that submitted nothing and says nothing is).
  std::chrono::milliseconds idle_timeout{std::chrono::minutes(10)};
  // A frame begun must be complete within this long (a slow or stalled sender of a large frame
  // cannot hold its buffer).
  std::chrono::milliseconds frame_timeout{std::chrono::seconds(30)};
  // A connection not marked authenticated (Session::mark_authenticated) this long after it was
  // accepted is closed; a TLS handshake counts within it. Silent connections cannot hold slots.
  std::chrono::milliseconds authentication_timeout{std::chrono::seconds(5)};
  // Responses queued and not yet taken by the peer: above this, no further request is read
  // (TCP flow control then holds the client back) until they drain. Leaves room for one
  // response of the largest frame on top.
  std::size_t pause_reading_above = std::size_t{1} << 20;
  // Above this (updates pushed from job threads to a peer that does not read), the connection
  // is closed and the reason logged.
  std::size_t close_above = std::size_t{64} << 20;
};

class Session final : public Peer, public std::enable_shared_from_this<Session> {
 public:
  // Called on the io_context thread, on this session's strand, once per Request.
  using Dispatch = std::function<void(Session&, const netmc::v1::Request&)>;
  // Called (on the strand) when a TLS session's handshake fails, with the peer and OpenSSL's reason.
  using HandshakeFailure = std::function<void(const std::string& peer, const std::string& reason)>;

  // The socket's executor should be a strand (ManagementServer gives each session its own) so
  // that the io_context may be run by several threads. With `tls`, the connection speaks TLS
  // (server side) and nothing is read or sent before the handshake has succeeded; a handshake
  // not done within the frame timeout closes it.
  Session(boost::asio::ip::tcp::socket socket, Dispatch dispatch, SessionLimits limits = {},
          std::shared_ptr<boost::asio::ssl::context> tls = nullptr, HandshakeFailure on_handshake_failure = {});

  // Starts reading; call once, after construction by std::make_shared.
  void start();

  // Thread-safe, from any thread: queues the response; responses leave in the order of the
  // calls. Dropped once the session is closed. Throws FrameError for a message over 16 MiB.
  void send(const netmc::v1::Response& response) override;

  // Thread-safe: false once the connection is closed or closing (by either side).
  bool open() const override { return open_.load(std::memory_order_acquire); }

  // Thread-safe: a session with work under way (a job it submitted) is not idle however long it
  // stays silent; each hold() is undone by one release().
  void hold() override { holds_.fetch_add(1, std::memory_order_acq_rel); }
  void release() override { holds_.fetch_sub(1, std::memory_order_acq_rel); }

  // Thread-safe: the peer proved it may use the server (showed the token; without a token file,
  // sent a well-formed request). Until then the authentication timeout applies and the server
  // may close this connection to make room for another.
  void mark_authenticated() { authenticated_.store(true, std::memory_order_release); }
  bool authenticated() const { return authenticated_.load(std::memory_order_acquire); }

  // Thread-safe: bytes of responses accepted by send() and not yet written to the socket.
  std::size_t queued_bytes() const { return queued_bytes_.load(std::memory_order_acquire); }

  // The peer's address (kept from the accept: still there after the socket closed).
  const boost::asio::ip::address& remote_address() const { return remote_address_; }
  // "address:port", for log lines.
  const std::string& remote() const { return remote_; }
  // Who submitted a job, for the job store and netmc jobs: "address:port".
  std::string name() const override { return remote_; }

  // Thread-safe: stops reading, sends the responses already queued, then closes the socket.
  void close();
  // Thread-safe: closes the socket now; queued responses are dropped (server shutdown).
  void abort();

 private:
  void handshake();
  void read();
  void dispatch_frames();  // the complete frames buffered, then read() unless paused or closing
  void watch();  // the limits' timer
  boost::asio::ip::tcp::socket& socket();  // the TCP socket under the stream
  void write_next();
  void drop_outbox();  // forgets what is queued, and its bytes
  void close_on_strand();
  void abort_on_strand();

  std::shared_ptr<boost::asio::ssl::context> tls_;  // kept for the stream's lifetime
  std::variant<boost::asio::ip::tcp::socket, boost::asio::ssl::stream<boost::asio::ip::tcp::socket>> stream_;
  Dispatch dispatch_;
  HandshakeFailure on_handshake_failure_;
  SessionLimits limits_;
  boost::asio::steady_timer watchdog_;
  std::chrono::steady_clock::time_point last_activity_;     // strand only
  std::chrono::steady_clock::time_point frame_started_;     // strand only; when buffered() became > 0
  std::chrono::steady_clock::time_point accepted_;          // the authentication timeout's start
  FrameDecoder decoder_;
  std::array<char, 8192> buffer_{};
  std::deque<std::string> outbox_;  // front() is being written
  bool closing_ = false;            // strand only
  bool ready_ = true;               // strand only; false until a TLS handshake has succeeded
  bool reading_paused_ = false;     // strand only; too many answers queued: no read under way
  std::atomic<bool> open_{true};
  std::atomic<int> holds_{0};
  std::atomic<bool> authenticated_{false};
  std::atomic<std::size_t> queued_bytes_{0};
  boost::asio::ip::address remote_address_;
  std::string remote_;
};

}  // namespace netmc::management
