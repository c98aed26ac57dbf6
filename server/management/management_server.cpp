#include "server/management/management_server.hpp"

namespace netmc::management {

namespace asio = boost::asio;
using asio::ip::tcp;

Session::Session(tcp::socket socket, Dispatch dispatch)
    : socket_(std::move(socket)), dispatch_(std::move(dispatch)) {}

void Session::start() { read(); }

void Session::read() {
  socket_.async_read_some(asio::buffer(buffer_), [self = shared_from_this()](
                                                     const boost::system::error_code& error,
                                                     std::size_t size) {
    if (error) return;  // closed by the peer or by stop()
    self->decoder_.feed(self->buffer_.data(), size);
    try {
      while (auto payload = self->decoder_.next()) {
        netmc::v1::Request request;
        if (!request.ParseFromString(*payload)) throw FrameError("request: not a netmc.v1.Request");
        self->dispatch_(*self, request);
      }
    } catch (const std::exception& problem) {
      netmc::v1::Response response;
      response.mutable_error()->set_message(problem.what());
      self->send(response);
      self->close();
      return;
    }
    self->read();
  });
}

void Session::send(const netmc::v1::Response& response) {
  auto frame = std::make_shared<std::string>(encode_frame(response));
  asio::post(socket_.get_executor(), [self = shared_from_this(), frame] {
    self->outbox_.push_back(std::move(*frame));
    if (self->outbox_.size() == 1) self->write_next();
  });
}

void Session::write_next() {
  asio::async_write(socket_, asio::buffer(outbox_.front()),
                    [self = shared_from_this()](const boost::system::error_code& error, std::size_t) {
                      if (error) {
                        self->outbox_.clear();
                        return;
                      }
                      self->outbox_.pop_front();
                      if (!self->outbox_.empty()) {
                        self->write_next();
                      } else if (self->closing_) {
                        boost::system::error_code ignored;
                        self->socket_.close(ignored);
                      }
                    });
}

void Session::close() {
  asio::post(socket_.get_executor(), [self = shared_from_this()] {
    // Queued responses (e.g. the error) leave first; write_next() closes after the last one.
    self->closing_ = true;
    if (self->outbox_.empty()) {
      boost::system::error_code ignored;
      self->socket_.close(ignored);
    }
  });
}

ManagementServer::ManagementServer(asio::io_context& io, const std::string& bind_address,
                                   std::uint16_t port, Handler handler)
    : acceptor_(io), handler_(std::move(handler)) {
  boost::system::error_code error;
  const auto address = asio::ip::make_address(bind_address, error);
  if (error) throw std::invalid_argument("--listen: '" + bind_address + "' is not an IP address");
  const tcp::endpoint endpoint(address, port);
  acceptor_.open(endpoint.protocol());
  acceptor_.set_option(tcp::acceptor::reuse_address(true));
  acceptor_.bind(endpoint, error);
  if (error) {
    throw std::runtime_error("--listen: cannot bind " + bind_address + ":" + std::to_string(port) +
                             ": " + error.message());
  }
  acceptor_.listen();
  accept();
}

std::uint16_t ManagementServer::port() const { return acceptor_.local_endpoint().port(); }

void ManagementServer::stop() {
  boost::system::error_code ignored;
  acceptor_.close(ignored);
}

void ManagementServer::accept() {
  acceptor_.async_accept([this](const boost::system::error_code& error, tcp::socket socket) {
    if (error) return;  // stopped
    std::make_shared<Session>(std::move(socket), handler_.on_request)->start();
    accept();
  });
}

}  // namespace netmc::management
