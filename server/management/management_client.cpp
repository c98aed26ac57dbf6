#include "server/management/management_client.hpp"

#include "server/management/access_token.hpp"
#include "server/management/host_port.hpp"
#include "server/management/tls_settings.hpp"

#include <array>
#include <cctype>
#include <stdexcept>

namespace netmc::management {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

// Boost's messages are strerror's ("Connection refused"); ours continue a sentence.
std::string describe(const boost::system::error_code& error) {
  std::string text = error.message();
  if (!text.empty()) text.front() = static_cast<char>(std::tolower(static_cast<unsigned char>(text.front())));
  return text;
}

// Runs io until its work is done or `timeout` passes; then cancels what is left via `cancel`
// and runs the cancelled handlers to completion. Returns true when it timed out.
template <typename Cancel>
bool run_with_timeout(asio::io_context& io, std::chrono::milliseconds timeout, Cancel cancel) {
  io.restart();
  io.run_for(timeout);
  const bool timed_out = !io.stopped();
  if (timed_out) {
    cancel();
    io.run();
  }
  io.restart();
  return timed_out;
}

using TlsStream = asio::ssl::stream<tcp::socket>;

std::shared_ptr<asio::ssl::context> client_tls(const std::optional<ClientTlsFiles>& files) {
  return files ? make_client_tls(*files) : nullptr;
}

}  // namespace

tcp::socket& ManagementClient::socket() {
  if (auto* plain = std::get_if<tcp::socket>(&stream_)) return *plain;
  return std::get<TlsStream>(stream_).next_layer();
}

ManagementClient::ManagementClient(const std::string& host_port,
                                   std::chrono::milliseconds connect_timeout)
    : name_(host_port),
      tls_files_(client_tls_from_environment()),
      tls_(client_tls(tls_files_)),
      stream_(tls_ ? decltype(stream_)(std::in_place_index<1>, io_, *tls_)
                   : decltype(stream_)(std::in_place_index<0>, io_)) {
  const HostPort target = parse_host_port(host_port, "--server");
  if (const auto token = client_token_from_environment()) token_ = token->value();

  boost::system::error_code error;
  tcp::resolver resolver(io_);
  tcp::resolver::results_type endpoints;
  resolver.async_resolve(target.host, target.port,
                         [&](const boost::system::error_code& result, tcp::resolver::results_type found) {
                           error = result;
                           endpoints = std::move(found);
                         });
  if (run_with_timeout(io_, connect_timeout, [&] { resolver.cancel(); })) {
    throw std::runtime_error("server " + name_ + ": cannot resolve '" + target.host + "' within " +
                             std::to_string(connect_timeout.count()) + " ms");
  }
  if (error) throw std::runtime_error("server " + name_ + ": cannot resolve '" + target.host + "': " + describe(error));

  asio::async_connect(socket(), endpoints,
                      [&](const boost::system::error_code& result, const tcp::endpoint&) { error = result; });
  if (run_with_timeout(io_, connect_timeout, [&] {
        boost::system::error_code ignored;
        socket().close(ignored);
      })) {
    throw std::runtime_error("server " + name_ + ": no connection within " +
                             std::to_string(connect_timeout.count()) + " ms");
  }
  if (error == asio::error::connection_refused) {
    // The usual cause is no server at all: say so, and how to start one there.
    throw std::runtime_error("server " + name_ + ": connection refused: no netmc-server listens there (start one with "
                             "`netmc-server --listen " + name_ + "`, or name another with --server or NETMC_SERVER)");
  }
  if (error) throw std::runtime_error("server " + name_ + ": " + describe(error));
  socket().set_option(tcp::no_delay(true), error);  // small frames: do not wait for Nagle
  if (!tls_) return;
  auto& stream = std::get<TlsStream>(stream_);
  // The certificate must name the host dialled (an IP address or a DNS name).
  stream.set_verify_callback(asio::ssl::host_name_verification(target.host));
  boost::system::error_code not_an_address;
  asio::ip::make_address(target.host, not_an_address);
  if (not_an_address) SSL_set_tlsext_host_name(stream.native_handle(), target.host.c_str());  // SNI: names only
  stream.async_handshake(asio::ssl::stream_base::client,
                         [&](const boost::system::error_code& result) { error = result; });
  if (run_with_timeout(io_, connect_timeout, [&] {
        boost::system::error_code ignored;
        socket().close(ignored);
      })) {
    throw std::runtime_error("server " + name_ + ": no TLS handshake within " +
                             std::to_string(connect_timeout.count()) + " ms");
  }
  if (error) {
    throw std::runtime_error("server " + name_ + ": TLS handshake failed: " + describe(error) +
                             " (NETMC_TLS_CA is " + tls_files_->ca_file + "; the server needs --tls-cert with a "
                             "certificate that CA signed for '" + target.host + "')");
  }
}

void ManagementClient::send(const netmc::v1::Request& request) {
  boost::system::error_code error;
  std::string frame;
  if (token_) {
    netmc::v1::Request with_token = request;
    with_token.set_token(*token_);
    frame = encode_frame(with_token);
  } else {
    frame = encode_frame(request);
  }
  std::visit([&](auto& stream) { asio::write(stream, asio::buffer(frame), error); }, stream_);
  if (error) throw std::runtime_error("server " + name_ + ": cannot send: " + describe(error));
}

std::optional<netmc::v1::Response> ManagementClient::receive(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::array<char, 8192> buffer{};
  while (true) {
    std::optional<std::string> payload;
    try {
      payload = decoder_.next();
    } catch (const FrameError& error) {
      throw std::runtime_error("server " + name_ + ": " + error.what());
    }
    if (payload) {
      netmc::v1::Response response;
      if (!response.ParseFromString(*payload)) {
        throw std::runtime_error("server " + name_ + ": frame of " + std::to_string(payload->size()) +
                                 " bytes is not a netmc.v1.Response");
      }
      return response;
    }
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left <= std::chrono::milliseconds::zero()) return std::nullopt;

    boost::system::error_code error;
    std::size_t received = 0;
    std::visit(
        [&](auto& stream) {
          stream.async_read_some(asio::buffer(buffer), [&](const boost::system::error_code& result, std::size_t size) {
            error = result;
            received = size;
          });
        },
        stream_);
    // On timeout, cancel the read but keep the connection; bytes that raced in are kept.
    run_with_timeout(io_, left, [&] {
      boost::system::error_code ignored;
      socket().cancel(ignored);
    });
    decoder_.feed(buffer.data(), received);
    answered_ = answered_ || received > 0;
    if (error == asio::error::operation_aborted) continue;  // the deadline check returns nullopt
    if (error == asio::error::eof || error == asio::ssl::error::stream_truncated) {
      // A TLS-only server closes a plain client at its first bytes, before any answer.
      throw std::runtime_error("server " + name_ + ": connection closed by the server" +
                               (answered_ || tls_ ? std::string()
                                                  : " before it answered (a server started with --tls-cert "
                                                    "speaks TLS only: set NETMC_TLS_CA to the CA file)"));
    }
    if (error && error.category() == asio::error::get_ssl_category()) {
      // In TLS 1.3 the server judges the client's certificate after the client's handshake.
      const std::string reason = describe(error);
      throw std::runtime_error("server " + name_ + ": TLS connection ended: " + reason +
                               (reason.find("certificate") != std::string::npos || reason.find("unknown ca") !=
                                                                                        std::string::npos
                                    ? " (a server started with --tls-client-ca serves only clients that show a "
                                      "certificate its CA signed: set NETMC_TLS_CERT and NETMC_TLS_KEY)"
                                    : ""));
    }
    if (error) throw std::runtime_error("server " + name_ + ": connection lost: " + describe(error));
  }
}

}  // namespace netmc::management
