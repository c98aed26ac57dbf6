#pragma once
// Synchronous client of the management endpoint, for the CLI: connecting and receiving have
// timeouts; errors are exceptions whose message names the server.

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio.hpp>
#include <boost/asio/ssl.hpp>

#include <chrono>
#include <optional>
#include <memory>
#include <string>
#include <variant>

#include "idl/management.pb.h"
#include "server/management/frame_codec.hpp"
#include "server/management/tls_settings.hpp"

namespace netmc::management {

class ManagementClient {
 public:
  // host_port: "HOST:PORT" (HOST a name or an IP address, "[v6]:PORT" for IPv6 literals).
  // Throws std::invalid_argument("--server: expected HOST:PORT, got '…'") for a malformed one
  // and std::runtime_error("server HOST:PORT: …") when it cannot resolve or connect in time.
  // With $NETMC_TLS_CA set, the connection speaks TLS and the server's certificate must be
  // signed by that CA and name HOST (tls_settings.hpp); otherwise it is refused. The client
  // shows $NETMC_TLS_CERT (key $NETMC_TLS_KEY) to a server that asks for a certificate.
  ManagementClient(const std::string& host_port, std::chrono::milliseconds connect_timeout);

  // Sends one framed request, with the token of $NETMC_TOKEN_FILE when that is set; throws
  // std::runtime_error naming the server when it fails.
  void send(const netmc::v1::Request& request);

  // The next response, or nullopt when none arrives within `timeout` (the connection stays
  // usable). Throws std::runtime_error naming the server when the server has closed the
  // connection or sent a malformed frame.
  std::optional<netmc::v1::Response> receive(std::chrono::milliseconds timeout);

 private:
  std::string name_;  // "host:port", for messages
  std::optional<std::string> token_;
  std::optional<ClientTlsFiles> tls_files_;  // when the connection speaks TLS
  boost::asio::io_context io_;
  std::shared_ptr<boost::asio::ssl::context> tls_;
  std::variant<boost::asio::ip::tcp::socket, boost::asio::ssl::stream<boost::asio::ip::tcp::socket>> stream_;
  FrameDecoder decoder_;
  bool answered_ = false;  // a byte came from the server

  boost::asio::ip::tcp::socket& socket();
};

}  // namespace netmc::management
