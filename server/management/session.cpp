#include "server/management/session.hpp"

#include <algorithm>

namespace netmc::management {

namespace asio = boost::asio;
using asio::ip::tcp;

Session::Session(tcp::socket socket, Dispatch dispatch, SessionLimits limits)
    : socket_(std::move(socket)),
      dispatch_(std::move(dispatch)),
      limits_(limits),
      watchdog_(socket_.get_executor()),
      last_activity_(std::chrono::steady_clock::now()) {}

void Session::start() {
  asio::dispatch(socket_.get_executor(), [self = shared_from_this()] {
    self->read();
    self->watch();
  });
}

void Session::watch() {
  // Often enough to hold each limit to within a quarter of itself, at most once a second.
  const auto period = std::clamp<std::chrono::milliseconds>(
      std::min(limits_.idle_timeout, limits_.frame_timeout) / 4, std::chrono::milliseconds(10), std::chrono::seconds(1));
  watchdog_.expires_after(period);
  watchdog_.async_wait([self = shared_from_this()](const boost::system::error_code& error) {
    if (error || self->closing_) return;
    const auto now = std::chrono::steady_clock::now();
    const bool idle = self->holds_.load(std::memory_order_acquire) == 0 &&
                      now - self->last_activity_ > self->limits_.idle_timeout;
    const bool stalled = self->decoder_.buffered() > 0 && now - self->frame_started_ > self->limits_.frame_timeout;
    if (idle || stalled) {
      self->abort_on_strand();
      return;
    }
    self->watch();
  });
}

void Session::read() {
  socket_.async_read_some(asio::buffer(buffer_), [self = shared_from_this()](
                                                     const boost::system::error_code& error,
                                                     std::size_t size) {
    if (error) {  // the peer closed (answer what is queued, then close) or we did
      if (error != asio::error::operation_aborted) self->close_on_strand();
      return;
    }
    if (self->closing_) return;
    self->last_activity_ = std::chrono::steady_clock::now();
    if (self->decoder_.buffered() == 0) self->frame_started_ = self->last_activity_;
    self->decoder_.feed(self->buffer_.data(), size);
    try {
      while (!self->closing_) {
        auto payload = self->decoder_.next();
        if (!payload) break;
        netmc::v1::Request request;
        if (!request.ParseFromString(*payload)) {
          throw FrameError("request: frame of " + std::to_string(payload->size()) +
                           " bytes is not a netmc.v1.Request");
        }
        if (self->dispatch_) self->dispatch_(*self, request);
        // The next frame's clock starts with its first byte, already here or still to come.
        self->frame_started_ = std::chrono::steady_clock::now();
      }
    } catch (const std::exception& problem) {
      // A malformed frame (or a handler that threw): say why, then close this connection.
      netmc::v1::Response response;
      response.mutable_error()->set_message(problem.what());
      self->send(response);
      self->close();
      return;
    }
    if (!self->closing_) self->read();
  });
}

void Session::send(const netmc::v1::Response& response) {
  if (!open()) return;
  auto frame = std::make_shared<std::string>(encode_frame(response));
  // post, never dispatch: a send from the io thread must not overtake earlier sends from others.
  asio::post(socket_.get_executor(), [self = shared_from_this(), frame] {
    if (self->closing_ || !self->socket_.is_open()) return;
    self->outbox_.push_back(std::move(*frame));
    if (self->outbox_.size() == 1) self->write_next();
  });
}

void Session::write_next() {
  asio::async_write(socket_, asio::buffer(outbox_.front()),
                    [self = shared_from_this()](const boost::system::error_code& error, std::size_t) {
                      if (error) {  // peer gone or socket closed: nothing more can leave
                        self->outbox_.clear();
                        self->abort_on_strand();
                        return;
                      }
                      self->outbox_.pop_front();
                      self->last_activity_ = std::chrono::steady_clock::now();
                      if (!self->outbox_.empty()) {
                        self->write_next();
                      } else if (self->closing_) {
                        self->abort_on_strand();  // the last queued response has left
                      }
                    });
}

void Session::close() {
  open_.store(false, std::memory_order_release);
  asio::post(socket_.get_executor(), [self = shared_from_this()] { self->close_on_strand(); });
}

void Session::abort() {
  open_.store(false, std::memory_order_release);
  asio::post(socket_.get_executor(), [self = shared_from_this()] { self->abort_on_strand(); });
}

void Session::close_on_strand() {
  open_.store(false, std::memory_order_release);
  closing_ = true;
  if (outbox_.empty()) abort_on_strand();  // otherwise write_next() closes after the last one
}

void Session::abort_on_strand() {
  open_.store(false, std::memory_order_release);
  closing_ = true;
  // outbox_ is left alone: a write in flight still refers to its front; that write completes
  // with an error and its handler clears the rest.
  boost::system::error_code ignored;
  watchdog_.cancel();
  socket_.shutdown(tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
}

}  // namespace netmc::management
