#pragma once
// Synchronous client of the management endpoint, for the CLI: every call has a timeout.

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio.hpp>

#include <chrono>
#include <optional>
#include <string>

#include "idl/management.pb.h"
#include "server/management/frame_codec.hpp"

namespace netmc::management {

class ManagementClient {
 public:
  // host_port: "HOST:PORT"; throws std::invalid_argument for a malformed one and
  // std::runtime_error naming the server when it cannot connect.
  ManagementClient(const std::string& host_port, std::chrono::milliseconds connect_timeout);

  void send(const netmc::v1::Request& request);
  // The next response, or nullopt when none arrives within `timeout`; throws
  // std::runtime_error when the server closes the connection.
  std::optional<netmc::v1::Response> receive(std::chrono::milliseconds timeout);

 private:
  std::string name_;
  boost::asio::io_context io_;
  boost::asio::ip::tcp::socket socket_;
  FrameDecoder decoder_;
};

}  // namespace netmc::management
