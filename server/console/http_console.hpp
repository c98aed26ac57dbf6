#pragma once
// The lab console over HTTP and WebSocket (Boost.Beast), on the server's io_context: the page
// and Debian's dygraphs as fixed files, /metrics and the API through ConsoleService, and /live,
// the WebSocket feed. docs/operations/console.md is the contract.
//
// Hostile input is bounded here: a request's header and body, the time to send it, the number of
// connections (at the cap the longest-waiting sender of a request makes room), the number of /live
// sessions, a WebSocket frame from the browser, and each browser's queue of messages (the oldest
// dropped first, counted). No request names a file: the files served are a fixed list.
// See docs/architecture.md, "Threads and queues".

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio.hpp>
#include <boost/asio/ssl.hpp>

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "server/console/console_service.hpp"
#include "server/console/request_origin_policy.hpp"

namespace netmc::console {

struct HttpConsoleLimits {
  // At the cap, a new connection closes the one that has waited longest for its request to come
  // in (a slow or idle sender), if any; so slow senders cannot lock a browser out.
  std::size_t max_connections = 64;
  // /live sessions, within max_connections: an upgrade beyond it gets 503, so that slow
  // readers of the feed leave room for the page's requests.
  std::size_t max_live_sessions = 32;
  std::chrono::milliseconds request_timeout{10000};  // to send one request (or finish TLS)
  std::size_t max_header_bytes = 8 * 1024;
  std::size_t max_body_bytes = 64 * 1024;
  std::size_t max_incoming_frame_bytes = 1024;        // from the browser over /live
  std::size_t max_queued_messages = 64;               // to one browser over /live
};

class HttpConsole {
 public:
  // Listens on bind_address:port (port 0: any free port; see port()). With `tls`, HTTPS and WSS
  // only. Every request, the page's files and /live's upgrade included, is refused (403) unless
  // `origins` allows its Host and Origin headers. `dygraphs_dir`: where Debian's libjs-dygraphs
  // is (read once, here). Throws std::runtime_error when it cannot listen.
  HttpConsole(boost::asio::io_context& io, ConsoleService& console, const std::string& bind_address,
              std::uint16_t port, RequestOriginPolicy origins, std::shared_ptr<boost::asio::ssl::context> tls = nullptr,
              HttpConsoleLimits limits = {}, const std::string& dygraphs_dir = "/usr/share/javascript/dygraphs");
  ~HttpConsole();
  HttpConsole(const HttpConsole&) = delete;
  HttpConsole& operator=(const HttpConsole&) = delete;

  std::uint16_t port() const { return port_; }
  // Stops accepting; open connections end with their next operation.
  void stop();

  struct State;

 private:
  std::shared_ptr<State> state_;
  std::uint16_t port_ = 0;
};

}  // namespace netmc::console
