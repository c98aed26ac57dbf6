#include "server/management/management_server.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include <chrono>
#include <vector>

namespace netmc::management {

namespace asio = boost::asio;
using asio::ip::tcp;

// Shared with the pending asynchronous operations, so none of them refers to the server object.
// Everything below is touched only on the acceptor's strand.
struct ManagementServer::State {
  State(asio::io_context& context, Handler on, ManagementLimits caps, std::shared_ptr<asio::ssl::context> tls_context,
        Session::HandshakeFailure on_failure)
      : io(context),
        acceptor(asio::make_strand(context)),
        retry(acceptor.get_executor()),
        handler(std::move(on)),
        limits(caps),
        tls(std::move(tls_context)),
        on_handshake_failure(std::move(on_failure)) {}

  asio::io_context& io;
  tcp::acceptor acceptor;
  asio::steady_timer retry;  // after a transient accept error (e.g. out of descriptors)
  Handler handler;
  ManagementLimits limits;
  std::shared_ptr<asio::ssl::context> tls;
  Session::HandshakeFailure on_handshake_failure;
  std::vector<std::weak_ptr<Session>> sessions;
  bool stopped = false;
};

namespace {

// Closes the oldest unauthenticated session (sessions are in the order accepted) that `which`
// selects; false when there is none.
template <typename Which>
bool close_oldest_unauthenticated(std::vector<std::weak_ptr<Session>>& sessions, const std::string& why, Which which) {
  for (auto it = sessions.begin(); it != sessions.end(); ++it) {
    const auto session = it->lock();
    if (!session || session->authenticated() || !which(*session)) continue;
    spdlog::info("management connection from {} closed: not authenticated yet, and {}", session->remote(), why);
    session->abort();
    sessions.erase(it);
    return true;
  }
  return false;
}

}  // namespace

bool ManagementServer::make_room(State& state, const asio::ip::address& address) {
  const auto& limits = state.limits;
  const auto unauthenticated = [&](auto&& which) {
    return static_cast<std::size_t>(std::count_if(state.sessions.begin(), state.sessions.end(), [&](const auto& s) {
      const auto session = s.lock();
      return session && !session->authenticated() && which(*session);
    }));
  };
  const auto from_address = [&](const Session& session) { return session.remote_address() == address; };
  const auto any = [](const Session&) { return true; };
  // A new connection is unauthenticated: room is made among the unauthenticated, oldest first.
  while (unauthenticated(from_address) >= limits.max_unauthenticated_per_address &&
         close_oldest_unauthenticated(state.sessions, "its address opened another beyond the limit of " +
                                                          std::to_string(limits.max_unauthenticated_per_address),
                                      from_address)) {
  }
  const std::size_t share = std::min(limits.max_unauthenticated, limits.max_connections);
  while ((unauthenticated(any) >= share || state.sessions.size() >= limits.max_connections) &&
         close_oldest_unauthenticated(state.sessions, "another connection came beyond the limit of " +
                                                          std::to_string(share) + " unauthenticated",
                                      any)) {
  }
  // Only authenticated clients left: the cap holds.
  return state.sessions.size() < limits.max_connections;
}

void ManagementServer::accept_after_error(const std::shared_ptr<State>& state) {
  state->retry.expires_after(std::chrono::milliseconds(100));
  state->retry.async_wait([state](const boost::system::error_code& error) {
    if (!error && !state->stopped) accept(state);
  });
}

void ManagementServer::accept(const std::shared_ptr<State>& state) {
  // Each session gets its own strand: its handlers never run concurrently.
  const asio::any_io_executor session_executor = asio::make_strand(state->io);
  state->acceptor.async_accept(session_executor, [state](const boost::system::error_code& error,
                                                         tcp::socket socket) {
    if (state->stopped || error == asio::error::operation_aborted) return;
    if (error) {
      accept_after_error(state);
      return;
    }
    std::erase_if(state->sessions, [](const std::weak_ptr<Session>& s) {
      const auto session = s.lock();
      return !session || !session->open();
    });
    auto session = std::make_shared<Session>(std::move(socket), state->handler.on_request, state->limits.session,
                                             state->tls, state->on_handshake_failure);
    if (make_room(*state, session->remote_address())) {
      state->sessions.push_back(session);
      session->start();
    } else {
      // Refused with a reason, not left waiting: the client reports it and exits.
      netmc::v1::Response refusal;
      refusal.mutable_error()->set_message("server busy: " + std::to_string(state->limits.max_connections) +
                                           " connections open, the limit; try again later");
      session->start();
      session->send(refusal);
      session->close();
    }
    accept(state);
  });
}

std::size_t ManagementServer::open_connections() const {
  return static_cast<std::size_t>(std::count_if(state_->sessions.begin(), state_->sessions.end(), [](const auto& s) {
    const auto session = s.lock();
    return session && session->open();
  }));
}

ManagementServer::ManagementServer(asio::io_context& io, const std::string& bind_address,
                                   std::uint16_t port, Handler handler, ManagementLimits limits,
                                   std::shared_ptr<asio::ssl::context> tls,
                                   Session::HandshakeFailure on_handshake_failure)
    : state_(std::make_shared<State>(io, std::move(handler), limits, std::move(tls),
                                     std::move(on_handshake_failure))) {
  boost::system::error_code error;
  const auto address = asio::ip::make_address(bind_address, error);
  if (error) throw std::invalid_argument("--listen: '" + bind_address + "' is not an IP address");
  const tcp::endpoint endpoint(address, port);
  const std::string where = (address.is_v6() ? "[" + bind_address + "]" : bind_address) + ":" +
                            std::to_string(port);
  auto& acceptor = state_->acceptor;
  acceptor.open(endpoint.protocol(), error);
  if (!error) acceptor.set_option(tcp::acceptor::reuse_address(true), error);
  if (!error) acceptor.bind(endpoint, error);
  if (!error) acceptor.listen(asio::socket_base::max_listen_connections, error);
  if (!error) port_ = acceptor.local_endpoint(error).port();
  if (error) throw std::runtime_error("--listen: cannot listen on " + where + ": " + error.message());
  accept(state_);
}

ManagementServer::~ManagementServer() { stop(); }

void ManagementServer::stop() {
  asio::dispatch(state_->acceptor.get_executor(), [state = state_] {
    if (state->stopped) return;
    state->stopped = true;
    boost::system::error_code ignored;
    state->acceptor.close(ignored);
    state->retry.cancel();
    for (const auto& weak : state->sessions) {
      if (auto session = weak.lock()) session->abort();
    }
    state->sessions.clear();
  });
}

}  // namespace netmc::management
