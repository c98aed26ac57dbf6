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

std::shared_ptr<ssl::context> make_server_tls(const std::string& certificate_file, const std::string& key_file,
                                              const std::string& client_ca_file) {
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
  if (!client_ca_file.empty()) {
    context->load_verify_file(client_ca_file, error);
    if (error) {
      throw std::invalid_argument("--tls-client-ca: " + client_ca_file +
                                  ": expected the PEM certificate of the CA that signs the clients': " +
                                  openssl_reason(error));
    }
    context->set_verify_mode(ssl::verify_peer | ssl::verify_fail_if_no_peer_cert);
  }
  return context;
}

std::shared_ptr<ssl::context> make_client_tls(const ClientTlsFiles& files) {
  auto context = tls13_context(ssl::context::tls_client);
  boost::system::error_code error;
  context->load_verify_file(files.ca_file, error);
  if (error) {
    throw std::invalid_argument("NETMC_TLS_CA: " + files.ca_file +
                                ": expected the PEM certificate of the CA that signed the server's: " +
                                openssl_reason(error));
  }
  context->set_verify_mode(ssl::verify_peer);
  if (!files.certificate_file.empty()) {
    context->use_certificate_chain_file(files.certificate_file, error);
    if (error) {
      throw std::invalid_argument("NETMC_TLS_CERT: " + files.certificate_file + ": expected a PEM certificate: " +
                                  openssl_reason(error));
    }
    context->use_private_key_file(files.key_file, ssl::context::pem, error);
    if (error) {
      throw std::invalid_argument("NETMC_TLS_KEY: " + files.key_file + ": expected the PEM private key of " +
                                  files.certificate_file + ": " + openssl_reason(error));
    }
  }
  return context;
}

std::optional<ClientTlsFiles> client_tls_from_environment() {
  const auto variable = [](const char* name) {
    const char* value = std::getenv(name);
    return std::string(value ? value : "");
  };
  ClientTlsFiles files{variable("NETMC_TLS_CA"), variable("NETMC_TLS_CERT"), variable("NETMC_TLS_KEY")};
  if (files.certificate_file.empty() != files.key_file.empty()) {
    throw std::invalid_argument(files.key_file.empty() ? "NETMC_TLS_CERT: needs NETMC_TLS_KEY (its private key)"
                                                       : "NETMC_TLS_KEY: needs NETMC_TLS_CERT (its certificate)");
  }
  if (files.ca_file.empty()) {
    if (!files.certificate_file.empty()) {
      throw std::invalid_argument("NETMC_TLS_CERT: needs NETMC_TLS_CA (the CA that signed the server's certificate)");
    }
    return std::nullopt;
  }
  return files;
}

std::string describe_server_tls(ssl::context& context) {
  std::string text = "TLS 1.3";
  std::array<char, 256> subject{};
  if (X509* certificate = SSL_CTX_get0_certificate(context.native_handle())) {
    X509_NAME_oneline(X509_get_subject_name(certificate), subject.data(), static_cast<int>(subject.size()));
    text += std::string(", certificate ") + subject.data();
  }
  if (SSL_CTX_get_verify_mode(context.native_handle()) & SSL_VERIFY_FAIL_IF_NO_PEER_CERT) {
    text += ", clients need a certificate of the client CA";
  }
  return text;
}

}  // namespace netmc::management
