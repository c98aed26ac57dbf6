#include "server/management/tls_settings.hpp"

#include <openssl/err.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>

#include <array>
#include <cstdlib>
#include <stdexcept>

namespace netmc::management {
namespace {

namespace ssl = boost::asio::ssl;

// Boost's text of an OpenSSL error; OpenSSL's own error queue is cleared for the next call.
std::string openssl_reason(const boost::system::error_code& error) {
  std::string reason = error.message();
  ERR_clear_error();
  return reason;
}

std::shared_ptr<ssl::context> tls13_context(ssl::context::method method) {
  auto context = std::make_shared<ssl::context>(method);
  // Both ends are netmc: nothing older than TLS 1.3 is needed or accepted.
  SSL_CTX_set_min_proto_version(context->native_handle(), TLS1_3_VERSION);
  context->set_options(ssl::context::default_workarounds | ssl::context::no_compression);
  return context;
}

}  // namespace

std::shared_ptr<ssl::context> make_server_tls(const std::string& certificate_file, const std::string& key_file) {
  auto context = tls13_context(ssl::context::tls_server);
  boost::system::error_code error;
  context->use_certificate_chain_file(certificate_file, error);
  if (error) {
    throw std::invalid_argument("--tls-cert: " + certificate_file + ": expected a PEM certificate (chain): " +
                                openssl_reason(error));
  }
  context->use_private_key_file(key_file, ssl::context::pem, error);
  if (error) {
    throw std::invalid_argument("--tls-key: " + key_file + ": expected the PEM private key of " + certificate_file +
                                ": " + openssl_reason(error));
  }
  return context;
}

std::shared_ptr<ssl::context> make_client_tls(const std::string& ca_file) {
  auto context = tls13_context(ssl::context::tls_client);
  boost::system::error_code error;
  context->load_verify_file(ca_file, error);
  if (error) {
    throw std::invalid_argument("NETMC_TLS_CA: " + ca_file + ": expected the PEM certificate of the CA that signed "
                                "the server's: " + openssl_reason(error));
  }
  context->set_verify_mode(ssl::verify_peer);
  return context;
}

std::optional<std::string> client_tls_ca_from_environment() {
  const char* path = std::getenv("NETMC_TLS_CA");
  if (!path || !*path) return std::nullopt;
  return std::string(path);
}

std::string describe_server_tls(ssl::context& context) {
  X509* certificate = SSL_CTX_get0_certificate(context.native_handle());
  if (!certificate) return "TLS 1.3";
  std::array<char, 256> subject{};
  X509_NAME_oneline(X509_get_subject_name(certificate), subject.data(), static_cast<int>(subject.size()));
  return std::string("TLS 1.3, certificate ") + subject.data();
}

}  // namespace netmc::management
