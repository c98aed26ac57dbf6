#include <utility>  // before Asio: Boost 1.74 needs it
// TLS on the management endpoint, against certificates made here with OpenSSL's API: a lab CA,
// the server's certificate for 127.0.0.1, one for another address and one from another CA.
// What travels between client and server is recorded by a relay in the middle.
#include <gtest/gtest.h>

#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "server/management/management_client.hpp"
#include "server/management/management_server.hpp"
#include "server/management/tls_settings.hpp"
#include "tests/support/io_thread.hpp"

namespace netmc::management {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;
using tcp = boost::asio::ip::tcp;

struct KeyDeleter {
  void operator()(EVP_PKEY* key) const { EVP_PKEY_free(key); }
};
struct CertificateDeleter {
  void operator()(X509* certificate) const { X509_free(certificate); }
};
using Key = std::unique_ptr<EVP_PKEY, KeyDeleter>;
using Certificate = std::unique_ptr<X509, CertificateDeleter>;

Key ec_key() { return Key(EVP_EC_gen("P-256")); }

// A certificate for `subject` with `key`, signed by `issuer_key` (self-signed when `issuer` is
// null); `alt_name` ("IP:127.0.0.1") makes it a leaf for `purpose` (serverAuth, clientAuth),
// otherwise a CA.
Certificate make_certificate(const std::string& subject, EVP_PKEY* key, X509* issuer, EVP_PKEY* issuer_key,
                             const std::string& alt_name, long serial, const std::string& purpose = "serverAuth") {
  Certificate certificate(X509_new());
  X509_set_version(certificate.get(), 2);
  ASN1_INTEGER_set(X509_get_serialNumber(certificate.get()), serial);
  X509_gmtime_adj(X509_getm_notBefore(certificate.get()), -60);
  X509_gmtime_adj(X509_getm_notAfter(certificate.get()), 3600);
  X509_set_pubkey(certificate.get(), key);
  X509_NAME* name = X509_get_subject_name(certificate.get());
  X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_ASC, reinterpret_cast<const unsigned char*>(subject.c_str()), -1,
                             -1, 0);
  X509_set_issuer_name(certificate.get(), issuer ? X509_get_subject_name(issuer) : name);
  X509V3_CTX context;
  X509V3_set_ctx_nodb(&context);
  X509V3_set_ctx(&context, issuer ? issuer : certificate.get(), certificate.get(), nullptr, nullptr, 0);
  const auto add = [&](int nid, const std::string& value) {
    X509_EXTENSION* extension = X509V3_EXT_conf_nid(nullptr, &context, nid, value.c_str());
    ASSERT_NE(extension, nullptr) << value;
    X509_add_ext(certificate.get(), extension, -1);
    X509_EXTENSION_free(extension);
  };
  if (alt_name.empty()) {
    add(NID_basic_constraints, "critical,CA:TRUE");
    add(NID_key_usage, "critical,keyCertSign,cRLSign");
  } else {
    add(NID_basic_constraints, "critical,CA:FALSE");
    add(NID_subject_alt_name, alt_name);
    add(NID_ext_key_usage, purpose);
  }
  EXPECT_GT(X509_sign(certificate.get(), issuer_key, EVP_sha256()), 0);
  return certificate;
}

void write_pem(const fs::path& path, X509* certificate, EVP_PKEY* key) {
  FILE* file = std::fopen(path.c_str(), "w");
  ASSERT_NE(file, nullptr);
  if (certificate) PEM_write_X509(file, certificate);
  if (key) PEM_write_PrivateKey(file, key, nullptr, nullptr, 0, nullptr, nullptr);
  std::fclose(file);
}

// ca.pem, server.pem/.key (for IP 127.0.0.1), elsewhere.pem/.key (for 127.0.0.2, same CA),
// stranger.pem/.key (for 127.0.0.1, another CA), client certificates operator.pem/.key (lab CA)
// and stranger-operator.pem/.key (another CA) in a fresh directory.
class TestPki {
 public:
  TestPki() : dir_(fs::temp_directory_path() / ("netmc_tls_test_" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
    const Key ca_key = ec_key(), other_ca_key = ec_key();
    const Certificate ca = make_certificate("netmc lab CA", ca_key.get(), nullptr, ca_key.get(), "", 1);
    const Certificate other_ca = make_certificate("other CA", other_ca_key.get(), nullptr, other_ca_key.get(), "", 2);
    write_pem(dir_ / "ca.pem", ca.get(), nullptr);
    const auto issue = [&](const std::string& name, const std::string& alt, X509* issuer, EVP_PKEY* issuer_key,
                           long serial, const std::string& purpose = "serverAuth") {
      const Key key = ec_key();
      const Certificate certificate = make_certificate(name, key.get(), issuer, issuer_key, alt, serial, purpose);
      write_pem(dir_ / (name + ".pem"), certificate.get(), nullptr);
      write_pem(dir_ / (name + ".key"), nullptr, key.get());
    };
    issue("server", "IP:127.0.0.1", ca.get(), ca_key.get(), 3);
    issue("elsewhere", "IP:127.0.0.2", ca.get(), ca_key.get(), 4);
    issue("stranger", "IP:127.0.0.1", other_ca.get(), other_ca_key.get(), 5);
    issue("operator", "DNS:operator", ca.get(), ca_key.get(), 6, "clientAuth");
    issue("stranger-operator", "DNS:operator", other_ca.get(), other_ca_key.get(), 7, "clientAuth");
  }
  ~TestPki() { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

// Sets an environment variable for one scope.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const std::string& value) : name_(name) { ::setenv(name, value.c_str(), 1); }
  ~ScopedEnvironment() { ::unsetenv(name_); }

 private:
  const char* name_;
};

using test_support::IoThread;

// Answers every request with "accepted, job 7".
ManagementServer::Handler accept_all() {
  return {[](Session& session, const netmc::v1::Request& request) {
    netmc::v1::Response response;
    response.set_request_id(request.request_id());
    response.mutable_accepted()->set_job_id(7);
    session.send(response);
  }};
}

netmc::v1::Request request_with_token(const std::string& token) {
  netmc::v1::Request request;
  request.set_request_id(1);
  request.set_token(token);
  request.mutable_status();
  return request;
}

// One connection relayed from a port of its own to `target`, recording what the client sent.
class RecordingRelay {
 public:
  explicit RecordingRelay(std::uint16_t target) : acceptor_(io_, {boost::asio::ip::make_address("127.0.0.1"), 0}) {
    port_ = acceptor_.local_endpoint().port();
    worker_ = std::thread([this, target] {
      tcp::socket client(io_), server(io_);
      acceptor_.accept(client);
      server.connect({boost::asio::ip::make_address("127.0.0.1"), target});
      std::thread back([&] { copy(server, client, nullptr); });
      copy(client, server, &sent_);
      back.join();
    });
  }
  ~RecordingRelay() { worker_.join(); }
  std::uint16_t port() const { return port_; }
  std::string sent() {
    std::lock_guard lock(mutex_);
    return sent_;
  }

 private:
  void copy(tcp::socket& from, tcp::socket& to, std::string* record) {
    std::array<char, 4096> buffer{};
    boost::system::error_code error;
    while (true) {
      const std::size_t size = from.read_some(boost::asio::buffer(buffer), error);
      if (error) break;
      if (record) {
        std::lock_guard lock(mutex_);
        record->append(buffer.data(), size);
      }
      boost::asio::write(to, boost::asio::buffer(buffer.data(), size), error);
      if (error) break;
    }
    boost::system::error_code ignored;
    to.shutdown(tcp::socket::shutdown_send, ignored);
  }

  boost::asio::io_context io_;
  tcp::acceptor acceptor_;
  std::uint16_t port_ = 0;
  std::thread worker_;
  std::mutex mutex_;
  std::string sent_;
};

const std::string kToken = "lab-secret-0123456789abcdef";

// The token travels encrypted with TLS and in clear without (the control that shows the relay
// would see it).
TEST(ManagementTls, RequestsTravelEncrypted) {
  TestPki pki;
  for (const bool tls : {false, true}) {
    IoThread runner;
    ManagementServer server(runner.io, "127.0.0.1", 0, accept_all(), {},
                            tls ? make_server_tls(pki.path("server.pem"), pki.path("server.key")) : nullptr);
    runner.start();
    std::string sent;
    {
      RecordingRelay relay(server.port());
      std::optional<ScopedEnvironment> ca;
      if (tls) ca.emplace("NETMC_TLS_CA", pki.path("ca.pem"));
      ManagementClient client("127.0.0.1:" + std::to_string(relay.port()), 2s);
      client.send(request_with_token(kToken));
      const auto response = client.receive(2s);
      ASSERT_TRUE(response && response->has_accepted()) << (tls ? "TLS" : "plain");
      EXPECT_EQ(response->accepted().job_id(), 7u);
      sent = relay.sent();
    }  // the client closes, the relay ends
    EXPECT_GT(sent.size(), kToken.size());
    EXPECT_EQ(sent.find(kToken) == std::string::npos, tls) << (tls ? "TLS" : "plain") << ": " << sent.size()
                                                            << " bytes sent";
  }
}

TEST(ManagementTls, APlainClientIsClosedBeforeAnyAnswerAndTheServerSaysWhy) {
  TestPki pki;
  IoThread runner;
  std::mutex mutex;
  std::string failure;
  ManagementServer server(runner.io, "127.0.0.1", 0, accept_all(), {},
                          make_server_tls(pki.path("server.pem"), pki.path("server.key")),
                          [&](const std::string& peer, const std::string& reason) {
                            std::lock_guard lock(mutex);
                            failure = peer + ": " + reason;
                          });
  runner.start();
  ManagementClient client("127.0.0.1:" + std::to_string(server.port()), 2s);
  client.send(request_with_token(kToken));
  try {
    client.receive(2s);
    FAIL() << "a plain client was answered by a TLS server";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("closed by the server before it answered (a server started with "
                                             "--tls-cert speaks TLS only: set NETMC_TLS_CA"),
              std::string::npos)
        << error.what();
  }
  std::lock_guard lock(mutex);
  EXPECT_NE(failure.find("127.0.0.1:"), std::string::npos) << failure;
  EXPECT_FALSE(failure.empty());
}

TEST(ManagementTls, TheClientRefusesACertificateForAnotherHostOrFromAnotherCa) {
  TestPki pki;
  for (const std::string name : {"elsewhere", "stranger"}) {
    IoThread runner;
    ManagementServer server(runner.io, "127.0.0.1", 0, accept_all(), {},
                            make_server_tls(pki.path(name + ".pem"), pki.path(name + ".key")));
    runner.start();
    ScopedEnvironment ca("NETMC_TLS_CA", pki.path("ca.pem"));
    try {
      ManagementClient client("127.0.0.1:" + std::to_string(server.port()), 2s);
      FAIL() << "trusted the " << name << " certificate";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find("TLS handshake failed: certificate verify failed"), std::string::npos)
          << name << ": " << error.what();
      EXPECT_NE(std::string(error.what()).find("NETMC_TLS_CA is " + pki.path("ca.pem")), std::string::npos)
          << error.what();
    }
  }
}

TEST(ManagementTls, ATlsClientOfAPlainServerSaysSo) {
  TestPki pki;
  IoThread runner;
  ManagementServer server(runner.io, "127.0.0.1", 0, accept_all());
  runner.start();
  ScopedEnvironment ca("NETMC_TLS_CA", pki.path("ca.pem"));
  try {
    ManagementClient client("127.0.0.1:" + std::to_string(server.port()), 2s);
    FAIL() << "a TLS handshake with a plain server succeeded";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("TLS handshake failed"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("the server needs --tls-cert"), std::string::npos) << error.what();
  }
}

TEST(ManagementTls, AConnectionThatNeverShakesHandsIsClosedAfterTheFrameTimeout) {
  TestPki pki;
  IoThread runner;
  ManagementLimits limits;
  limits.session.frame_timeout = 300ms;
  ManagementServer server(runner.io, "127.0.0.1", 0, accept_all(), limits,
                          make_server_tls(pki.path("server.pem"), pki.path("server.key")));
  runner.start();
  boost::asio::io_context io;
  tcp::socket socket(io);
  socket.connect({boost::asio::ip::make_address("127.0.0.1"), server.port()});
  const auto started = std::chrono::steady_clock::now();
  std::array<char, 64> buffer{};
  boost::system::error_code error;
  while (!error) socket.read_some(boost::asio::buffer(buffer), error);
  const auto closed_after = std::chrono::steady_clock::now() - started;
  EXPECT_EQ(error, boost::asio::error::eof);
  EXPECT_GE(closed_after, 250ms);
  EXPECT_LT(closed_after, 2s);
}

TEST(ManagementTls, BadCertificateOrKeyFilesNameTheFlag) {
  TestPki pki;
  const auto error_of = [](const std::function<void()>& make) {
    try {
      make();
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(error_of([&] { make_server_tls(pki.path("missing.pem"), pki.path("server.key")); }).rfind(
                "--tls-cert: " + pki.path("missing.pem") + ": expected a PEM certificate", 0),
            0u);
  EXPECT_EQ(error_of([&] { make_server_tls(pki.path("server.pem"), pki.path("server.pem")); }).rfind("--tls-key: ", 0),
            0u);
  EXPECT_EQ(error_of([&] { make_server_tls(pki.path("server.pem"), pki.path("elsewhere.key")); })
                .rfind("--tls-key: " + pki.path("elsewhere.key") + ": expected the PEM private key of " +
                           pki.path("server.pem"),
                       0),
            0u);
  EXPECT_EQ(error_of([&] { make_client_tls({pki.path("server.key"), "", ""}); })
                .rfind("NETMC_TLS_CA: " + pki.path("server.key"), 0),
            0u);
  EXPECT_EQ(error_of([&] { make_client_tls({pki.path("ca.pem"), pki.path("operator.pem"), pki.path("server.key")}); })
                .rfind("NETMC_TLS_KEY: " + pki.path("server.key") + ": expected the PEM private key of", 0),
            0u);
  EXPECT_EQ(error_of([&] { make_server_tls(pki.path("server.pem"), pki.path("server.key"), pki.path("none.pem")); })
                .rfind("--tls-client-ca: " + pki.path("none.pem"), 0),
            0u);
  {
    ScopedEnvironment certificate("NETMC_TLS_CERT", pki.path("operator.pem"));
    EXPECT_EQ(error_of([] { client_tls_from_environment(); }), "NETMC_TLS_CERT: needs NETMC_TLS_KEY (its private key)");
    ScopedEnvironment key("NETMC_TLS_KEY", pki.path("operator.key"));
    EXPECT_EQ(error_of([] { client_tls_from_environment(); }),
              "NETMC_TLS_CERT: needs NETMC_TLS_CA (the CA that signed the server's certificate)");
  }
}

// --tls-client-ca: only a client showing a certificate of that CA is served.
TEST(ManagementTls, AServerThatAsksForClientCertificatesServesOnlyTheLabsClients) {
  TestPki pki;
  IoThread runner;
  std::atomic<int> failures{0};
  ManagementServer server(runner.io, "127.0.0.1", 0, accept_all(), {},
                          make_server_tls(pki.path("server.pem"), pki.path("server.key"), pki.path("ca.pem")),
                          [&](const std::string&, const std::string&) { ++failures; });
  runner.start();
  const std::string where = "127.0.0.1:" + std::to_string(server.port());
  ScopedEnvironment ca("NETMC_TLS_CA", pki.path("ca.pem"));
  // The outcome of one request: "accepted", or what the client saw.
  const auto outcome = [&]() -> std::string {
    try {
      ManagementClient client(where, 2s);
      client.send(request_with_token(kToken));
      const auto response = client.receive(2s);
      return response && response->has_accepted() ? "accepted" : "no answer";
    } catch (const std::runtime_error& error) {
      return error.what();
    }
  };
  EXPECT_NE(outcome().find("certificate required"), std::string::npos) << "without a client certificate";
  {
    ScopedEnvironment certificate("NETMC_TLS_CERT", pki.path("stranger-operator.pem"));
    ScopedEnvironment key("NETMC_TLS_KEY", pki.path("stranger-operator.key"));
    const std::string seen = outcome();
    EXPECT_NE(seen, "accepted") << "a client certificate of another CA";
    EXPECT_NE(seen.find("TLS"), std::string::npos) << seen;
  }
  ScopedEnvironment certificate("NETMC_TLS_CERT", pki.path("operator.pem"));
  ScopedEnvironment key("NETMC_TLS_KEY", pki.path("operator.key"));
  EXPECT_EQ(outcome(), "accepted");
  EXPECT_EQ(failures.load(), 2);
}

}  // namespace
}  // namespace netmc::management
