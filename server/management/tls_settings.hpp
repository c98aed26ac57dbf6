#pragma once
// TLS for the management endpoint (TLS 1.3 only; OpenSSL through Boost.Asio). The server shows a
// certificate (netmc-server --tls-cert/--tls-key, e.g. from scripts/make-lab-pki.sh
// --management HOST); a client trusts the CA in the file named by $NETMC_TLS_CA and checks that
// the certificate names the host it dialled. Requests (and the token in them) then travel
// encrypted.

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio/ssl.hpp>

#include <memory>
#include <optional>
#include <string>

namespace netmc::management {

// Throws std::invalid_argument naming the flag and the file when a file cannot be read, is not
// PEM of the expected kind, or the key does not belong to the certificate.
std::shared_ptr<boost::asio::ssl::context> make_server_tls(const std::string& certificate_file,
                                                           const std::string& key_file);
// Throws std::invalid_argument naming NETMC_TLS_CA and the file when it holds no certificate.
std::shared_ptr<boost::asio::ssl::context> make_client_tls(const std::string& ca_file);

// The CA file a client trusts: $NETMC_TLS_CA, if set and not empty.
std::optional<std::string> client_tls_ca_from_environment();

// "TLS 1.3, certificate CN=..., valid until ..." of a server context, for its start line.
std::string describe_server_tls(boost::asio::ssl::context& context);

}  // namespace netmc::management
