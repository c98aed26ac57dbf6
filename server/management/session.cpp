#include "server/management/session.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace netmc::management {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

using TlsStream = asio::ssl::stream<tcp::socket>;
using Stream = std::variant<tcp::socket, TlsStream>;

Stream make_stream(tcp::socket socket, const std::shared_ptr<asio::ssl::context>& tls) {
  if (tls) return Stream(std::in_place_index<1>, std::move(socket), *tls);
  return Stream(std::in_place_index<0>, std::move(socket));
}

}  // namespace

Session::Session(tcp::socket socket, Dispatch dispatch, SessionLimits limits,
                 std::shared_ptr<asio::ssl::context> tls, HandshakeFailure on_handshake_failure)
    : tls_(std::move(tls)),
      stream_(make_stream(std::move(socket), tls_)),
      dispatch_(std::move(dispatch)),
      on_handshake_failure_(std::move(on_handshake_failure)),
      limits_(limits),
      watchdog_(this->socket().get_executor()),
      last_activity_(std::chrono::steady_clock::now()),
      accepted_(last_activity_),
      ready_(!tls_) {
  boost::system::error_code ignored;
  const auto peer = this->socket().remote_endpoint(ignored);
  if (!ignored) {
    remote_address_ = peer.address();
    remote_ = (remote_address_.is_v6() ? "[" + remote_address_.to_string() + "]" : remote_address_.to_string()) +
              ":" + std::to_string(peer.port());
  } else {
    remote_ = "?";
  }
}

tcp::socket& Session::socket() {
  if (auto* plain = std::get_if<tcp::socket>(&stream_)) return *plain;
  return std::get<TlsStream>(stream_).next_layer();
}

void Session::start() {
  asio::dispatch(socket().get_executor(), [self = shared_from_this()] {
    if (self->ready_) {
      self->read();
    } else {
      self->handshake();
    }
    self->watch();
  });
}

void Session::handshake() {
  // A handshake counts as a frame in progress: it must be done within the frame timeout.
  frame_started_ = std::chrono::steady_clock::now();
  std::get<TlsStream>(stream_).async_handshake(
      asio::ssl::stream_base::server, [self = shared_from_this()](const boost::system::error_code& error) {
        if (self->closing_) {
          if (!self->outbox_.empty() && !error) {
            self->ready_ = true;
            self->write_next();  // what was queued before the close (a refusal), then closed
          } else {
            self->drop_outbox();  // no write was started: nothing refers to it
            self->abort_on_strand();
          }
          return;
        }
        if (error) {
          if (self->on_handshake_failure_) {
            boost::system::error_code ignored;
            const auto peer = self->socket().remote_endpoint(ignored);
            self->on_handshake_failure_(ignored ? "?" : peer.address().to_string() + ":" + std::to_string(peer.port()),
                                        error.message());
          }
          self->abort_on_strand();
          return;
        }
        self->ready_ = true;
        self->last_activity_ = std::chrono::steady_clock::now();
        if (!self->outbox_.empty()) self->write_next();
        self->read();
      });
}

void Session::watch() {
  // Often enough to hold each limit to within a quarter of itself, at most once a second.
  const auto period = std::clamp<std::chrono::milliseconds>(
      std::min({limits_.idle_timeout, limits_.frame_timeout, limits_.authentication_timeout}) / 4,
      std::chrono::milliseconds(10), std::chrono::seconds(1));
  watchdog_.expires_after(period);
  watchdog_.async_wait([self = shared_from_this()](const boost::system::error_code& error) {
    if (error || self->closing_) return;
    const auto now = std::chrono::steady_clock::now();
    const bool idle = self->holds_.load(std::memory_order_acquire) == 0 &&
                      now - self->last_activity_ > self->limits_.idle_timeout;
    // Not while reading is paused: then the server, not the peer, holds the frame back.
    const bool stalled = (self->decoder_.buffered() > 0 || !self->ready_) && !self->reading_paused_ &&
                         now - self->frame_started_ > self->limits_.frame_timeout;
    if (!self->authenticated() && now - self->accepted_ > self->limits_.authentication_timeout) {
      spdlog::info("management connection from {} closed: not authenticated within {} ms", self->remote_,
                   self->limits_.authentication_timeout.count());
      self->abort_on_strand();
      return;
    }
    if (idle || stalled) {
      self->abort_on_strand();
      return;
    }
    self->watch();
  });
}

void Session::read() {
  const auto on_read = [self = shared_from_this()](const boost::system::error_code& error, std::size_t size) {
    if (error) {  // the peer closed (answer what is queued, then close) or we did
      if (error != asio::error::operation_aborted) self->close_on_strand();
      return;
    }
    if (self->closing_) return;
    self->last_activity_ = std::chrono::steady_clock::now();
    if (self->decoder_.buffered() == 0) self->frame_started_ = self->last_activity_;
    self->decoder_.feed(self->buffer_.data(), size);
    self->dispatch_frames();
  };
  std::visit([&](auto& stream) { stream.async_read_some(asio::buffer(buffer_), on_read); }, stream_);
}

void Session::dispatch_frames() {
  try {
    while (!closing_) {
      // Answers the peer has not taken yet: read no further request until they drain (TCP flow
      // control then holds the peer back); write_next() resumes here.
      if (queued_bytes() > limits_.pause_reading_above) {
        reading_paused_ = true;
        return;
      }
      auto payload = decoder_.next();
      if (!payload) break;
      netmc::v1::Request request;
      if (!request.ParseFromString(*payload)) {
        throw FrameError("request: frame of " + std::to_string(payload->size()) + " bytes is not a netmc.v1.Request");
      }
      if (dispatch_) dispatch_(*this, request);
      // The next frame's clock starts with its first byte, already here or still to come.
      frame_started_ = std::chrono::steady_clock::now();
    }
  } catch (const std::exception& problem) {
    // A malformed frame (or a handler that threw): say why, then close this connection.
    netmc::v1::Response response;
    response.mutable_error()->set_message(problem.what());
    send(response);
    close();
    return;
  }
  if (!closing_) read();
}

void Session::send(const netmc::v1::Response& response) {
  if (!open()) return;
  auto frame = std::make_shared<std::string>(encode_frame(response));
  // Counted from here (the posted frame is memory too) until written or dropped.
  const std::size_t queued = queued_bytes_.fetch_add(frame->size(), std::memory_order_acq_rel) + frame->size();
  if (queued > limits_.close_above) {
    // Only updates pushed from other threads get here (requests are not read above the pause
    // threshold): the peer does not take what it asked for.
    queued_bytes_.fetch_sub(frame->size(), std::memory_order_acq_rel);
    if (open_.exchange(false, std::memory_order_acq_rel)) {
      spdlog::warn("management connection from {} closed: {} bytes of responses queued that it does not read "
                   "(the limit is {})",
                   remote_, queued, limits_.close_above);
      asio::post(socket().get_executor(), [self = shared_from_this()] { self->abort_on_strand(); });
    }
    return;
  }
  // post, never dispatch: a send from the io thread must not overtake earlier sends from others.
  asio::post(socket().get_executor(), [self = shared_from_this(), frame] {
    if (self->closing_ || !self->socket().is_open()) {
      self->queued_bytes_.fetch_sub(frame->size(), std::memory_order_acq_rel);
      return;
    }
    self->outbox_.push_back(std::move(*frame));
    if (self->outbox_.size() == 1 && self->ready_) self->write_next();
  });
}

void Session::write_next() {
  const auto on_written = [self = shared_from_this()](const boost::system::error_code& error, std::size_t) {
    if (error) {  // peer gone or socket closed: nothing more can leave
      self->drop_outbox();
      self->abort_on_strand();
      return;
    }
    self->queued_bytes_.fetch_sub(self->outbox_.front().size(), std::memory_order_acq_rel);
    self->outbox_.pop_front();
    self->last_activity_ = std::chrono::steady_clock::now();
    if (!self->outbox_.empty()) {
      self->write_next();
    } else if (self->closing_) {
      self->abort_on_strand();  // the last queued response has left
      return;
    }
    if (self->reading_paused_ && !self->closing_ && self->queued_bytes() <= self->limits_.pause_reading_above) {
      self->reading_paused_ = false;
      self->frame_started_ = self->last_activity_;
      self->dispatch_frames();  // what is buffered first, then reading again
    }
  };
  std::visit([&](auto& stream) { asio::async_write(stream, asio::buffer(outbox_.front()), on_written); }, stream_);
}

void Session::drop_outbox() {
  for (const auto& frame : outbox_) queued_bytes_.fetch_sub(frame.size(), std::memory_order_acq_rel);
  outbox_.clear();
}

void Session::close() {
  open_.store(false, std::memory_order_release);
  asio::post(socket().get_executor(), [self = shared_from_this()] { self->close_on_strand(); });
}

void Session::abort() {
  open_.store(false, std::memory_order_release);
  asio::post(socket().get_executor(), [self = shared_from_this()] { self->abort_on_strand(); });
}

void Session::close_on_strand() {
  open_.store(false, std::memory_order_release);
  closing_ = true;
  // Otherwise write_next() closes after the last one (or the handshake, if it is still under way).
  if (outbox_.empty() && ready_) abort_on_strand();
}

void Session::abort_on_strand() {
  open_.store(false, std::memory_order_release);
  closing_ = true;
  // outbox_ is left alone: a write in flight still refers to its front; that write completes
  // with an error and its handler clears the rest.
  boost::system::error_code ignored;
  watchdog_.cancel();
  socket().shutdown(tcp::socket::shutdown_both, ignored);
  socket().close(ignored);
}

}  // namespace netmc::management
