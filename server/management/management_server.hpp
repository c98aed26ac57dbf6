#pragma once
// The management endpoint of netmc-server: accepts TCP connections and dispatches each framed
// Request to a handler on the io_context thread. Sessions may be answered from any thread.

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "idl/management.pb.h"
#include "server/management/session.hpp"

namespace netmc::management {

// What one server gives its clients at most.
struct ManagementLimits {
  // Open connections; one more is answered with an error and closed. With 16 MiB frames this
  // bounds the memory that partial frames can take.
  std::size_t max_connections = 32;
  // Connections not yet authenticated (SessionLimits::authentication_timeout), at most this many
  // (and at most max_connections); one more closes the oldest of them rather than being refused,
  // so a client with the token always gets in while the slots are held by silent connections.
  std::size_t max_unauthenticated = 16;
  // The same, counted per remote address: one host cannot take the whole share. Authenticated
  // connections are not counted per address (local clients and clients behind one NAT share it).
  std::size_t max_unauthenticated_per_address = 8;
  SessionLimits session;
};

class ManagementServer {
 public:
  struct Handler {
    std::function<void(Session&, const netmc::v1::Request&)> on_request;
  };

  // Listens on bind_address:port (an IP address; port 0 = ephemeral, see port()). Throws
  // std::invalid_argument for a bind_address that is not an IP address and std::runtime_error
  // when it cannot listen. The io_context is run by the caller. With `tls` every connection
  // speaks TLS (tls_settings.hpp) and a client that does not is closed at its first bytes
  // (`on_handshake_failure`, optional, says who and why).
  ManagementServer(boost::asio::io_context& io, const std::string& bind_address, std::uint16_t port,
                   Handler handler, ManagementLimits limits = {},
                   std::shared_ptr<boost::asio::ssl::context> tls = nullptr,
                   Session::HandshakeFailure on_handshake_failure = {});
  ~ManagementServer();  // stop()
  ManagementServer(const ManagementServer&) = delete;
  ManagementServer& operator=(const ManagementServer&) = delete;

  // The port listened on (the ephemeral one chosen when constructed with 0).
  std::uint16_t port() const { return port_; }
  // Open connections; call on the io_context's thread.
  std::size_t open_connections() const;

  // Thread-safe, idempotent: stops accepting and closes every open session (queued responses
  // are dropped). Once the handler's own work is done, io_context::run() returns.
  void stop();

 private:
  struct State;
  static void accept(const std::shared_ptr<State>& state);
  static void accept_after_error(const std::shared_ptr<State>& state);
  // Closes unauthenticated sessions as the limits ask before one more from `address` is taken;
  // false when the cap is held by authenticated sessions alone (the new one is refused).
  static bool make_room(State& state, const boost::asio::ip::address& address);

  std::shared_ptr<State> state_;
  std::uint16_t port_ = 0;
};

}  // namespace netmc::management
