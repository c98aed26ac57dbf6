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
// PEM of the expected kind, or the key does not belong to the certificate. With
// `client_ca_file` (--tls-client-ca), a client must show a certificate that CA signed.
std::shared_ptr<boost::asio::ssl::context> make_server_tls(const std::string& certificate_file,
                                                           const std::string& key_file,
                                                           const std::string& client_ca_file = "");

// What a client brings to a TLS server: the CA it trusts ($NETMC_TLS_CA) and, for a server that
// asks for one, its own certificate and key ($NETMC_TLS_CERT, $NETMC_TLS_KEY).
struct ClientTlsFiles {
  std::string ca_file;
  std::string certificate_file;  // "": none
  std::string key_file;
};
// Throws std::invalid_argument naming the variable and the file that is not what it should be.
std::shared_ptr<boost::asio::ssl::context> make_client_tls(const ClientTlsFiles& files);

// From the environment, when $NETMC_TLS_CA is set and not empty; throws std::invalid_argument
// when only one of $NETMC_TLS_CERT and $NETMC_TLS_KEY is set, or either without $NETMC_TLS_CA.
std::optional<ClientTlsFiles> client_tls_from_environment();

// "TLS 1.3, certificate /CN=...[, clients need a certificate of /CN=...]" of a server context,
// for its start line.
std::string describe_server_tls(boost::asio::ssl::context& context);

}  // namespace netmc::management
