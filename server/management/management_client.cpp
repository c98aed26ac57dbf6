#include "server/management/management_client.hpp"

#include <array>

namespace netmc::management {

namespace asio = boost::asio;
using asio::ip::tcp;

ManagementClient::ManagementClient(const std::string& host_port,
                                   std::chrono::milliseconds connect_timeout)
    : name_(host_port), socket_(io_) {
  const auto colon = host_port.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == host_port.size() ||
      host_port.find_first_not_of("0123456789", colon + 1) != std::string::npos) {
    throw std::invalid_argument("--server: expected HOST:PORT, got '" + host_port + "'");
  }
  tcp::resolver resolver(io_);
  boost::system::error_code error;
  const auto endpoints = resolver.resolve(host_port.substr(0, colon), host_port.substr(colon + 1), error);
  if (error) throw std::runtime_error("server " + name_ + ": " + error.message());
  boost::system::error_code connect_error = asio::error::timed_out;
  asio::async_connect(socket_, endpoints,
                      [&](const boost::system::error_code& result, const tcp::endpoint&) {
                        connect_error = result;
                      });
  io_.run_for(connect_timeout);
  if (!io_.stopped()) {
    socket_.close(error);
    io_.run();
  }
  io_.restart();
  if (connect_error) throw std::runtime_error("server " + name_ + ": " + connect_error.message());
}

void ManagementClient::send(const netmc::v1::Request& request) {
  boost::system::error_code error;
  asio::write(socket_, asio::buffer(encode_frame(request)), error);
  if (error) throw std::runtime_error("server " + name_ + ": " + error.message());
}

std::optional<netmc::v1::Response> ManagementClient::receive(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::array<char, 8192> buffer{};
  while (true) {
    if (auto payload = decoder_.next()) {
      netmc::v1::Response response;
      if (!response.ParseFromString(*payload)) {
        throw std::runtime_error("server " + name_ + ": malformed response");
      }
      return response;
    }
    const auto left = deadline - std::chrono::steady_clock::now();
    if (left <= std::chrono::steady_clock::duration::zero()) return std::nullopt;
    boost::system::error_code read_error = asio::error::timed_out;
    std::size_t received = 0;
    socket_.async_read_some(asio::buffer(buffer),
                            [&](const boost::system::error_code& result, std::size_t size) {
                              read_error = result;
                              received = size;
                            });
    io_.run_for(std::chrono::duration_cast<std::chrono::milliseconds>(left));
    if (!io_.stopped()) {
      socket_.cancel();  // timed out: finish the cancelled read, keep the connection
      io_.run();
    }
    io_.restart();
    if (read_error == asio::error::operation_aborted) return std::nullopt;
    if (read_error) throw std::runtime_error("server " + name_ + ": connection closed (" + read_error.message() + ")");
    decoder_.feed(buffer.data(), received);
  }
}

}  // namespace netmc::management
