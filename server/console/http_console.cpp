#include "server/console/http_console.hpp"

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <spdlog/spdlog.h>

#include <deque>
#include <fstream>
#include <functional>
#include <list>
#include <map>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "server/console/console_assets.hpp"

namespace netmc::console {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using PlainStream = beast::tcp_stream;
using TlsStream = beast::ssl_stream<beast::tcp_stream>;

constexpr std::size_t kMaxDygraphsFile = 4 * 1024 * 1024;

std::string read_bounded(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream out;
  out << in.rdbuf();
  std::string text = out.str();
  return text.size() > kMaxDygraphsFile ? std::string() : text;
}

}  // namespace

struct HttpConsole::State {
  State(asio::io_context& context, ConsoleService& service, RequestOriginPolicy origin_policy,
        std::shared_ptr<asio::ssl::context> tls_context, HttpConsoleLimits caps)
      : io(context),
        console(service),
        acceptor(context),
        origins(std::move(origin_policy)),
        tls(std::move(tls_context)),
        limits(caps) {}

  // A fixed file of the console: what it is served as.
  struct StaticFile {
    std::string content_type;
    std::string body;
  };

  asio::io_context& io;
  ConsoleService& console;
  tcp::acceptor acceptor;
  RequestOriginPolicy origins;
  std::shared_ptr<asio::ssl::context> tls;
  HttpConsoleLimits limits;
  std::map<std::string, StaticFile> files;  // by exact request target
  std::size_t connections = 0;
  std::size_t live_sessions = 0;
  // Connections waiting for (the rest of) a request, oldest first: each entry closes its one.
  std::list<std::function<void()>> waiting_for_request;
  bool stopped = false;
};

namespace {

using State = HttpConsole::State;

// Counts a connection for the limit and /metrics while it lives.
class ConnectionCount {
 public:
  explicit ConnectionCount(std::shared_ptr<State> state) : state_(std::move(state)) {
    ++state_->connections;
    state_->console.count_connection(+1);
  }
  ~ConnectionCount() {
    --state_->connections;
    state_->console.count_connection(-1);
  }
  ConnectionCount(const ConnectionCount&) = delete;
  ConnectionCount& operator=(const ConnectionCount&) = delete;
  const std::shared_ptr<State>& state() const { return state_; }

 private:
  std::shared_ptr<State> state_;
};

template <class Stream>
void set_timeout(Stream& stream, std::chrono::milliseconds timeout) {
  beast::get_lowest_layer(stream).expires_after(timeout);
}

// /live: the feed, server to browser; frames from the browser are read (bounded) and ignored.
template <class Stream>
class LiveSession : public std::enable_shared_from_this<LiveSession<Stream>> {
 public:
  LiveSession(Stream&& stream, std::unique_ptr<ConnectionCount> count)
      : ws_(std::move(stream)), count_(std::move(count)) {
    ++state().live_sessions;
  }
  ~LiveSession() { --state().live_sessions; }
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  void run(http::request<http::string_body> request) {
    beast::get_lowest_layer(ws_).expires_never();  // the WebSocket's own timeouts from here
    websocket::stream_base::timeout timeouts = websocket::stream_base::timeout::suggested(beast::role_type::server);
    timeouts.idle_timeout = std::chrono::seconds(30);  // with pings: a browser gone dark is let go
    timeouts.keep_alive_pings = true;
    ws_.set_option(timeouts);
    ws_.read_message_max(state().limits.max_incoming_frame_bytes);
    ws_.async_accept(request, [self = this->shared_from_this()](beast::error_code error) {
      if (error) return;
      self->on_open();
    });
  }

 private:
  State& state() { return *count_->state(); }

  void on_open() {
    std::weak_ptr<LiveSession> weak = this->shared_from_this();
    subscription_ = state().console.subscribe([weak](const std::shared_ptr<const std::string>& message) {
      if (const auto self = weak.lock()) self->enqueue(message);
    });
    subscribed_ = true;
    enqueue(std::make_shared<const std::string>(state().console.hello()));
    read();
  }

  void read() {
    ws_.async_read(incoming_, [self = this->shared_from_this()](beast::error_code error, std::size_t) {
      if (error) {
        self->close();
        return;
      }
      self->incoming_.consume(self->incoming_.size());
      self->read();
    });
  }

  void enqueue(const std::shared_ptr<const std::string>& message) {
    if (closed_) return;
    // Bounded: past the limit the oldest message not on the wire goes (counted).
    if (queue_.size() >= state().limits.max_queued_messages) {
      const auto oldest = writing_ ? std::next(queue_.begin()) : queue_.begin();
      if (oldest != queue_.end()) {
        queue_.erase(oldest);
        state().console.count_dropped_messages(1);
      }
    }
    queue_.push_back(message);
    if (!writing_) write_next();
  }

  void write_next() {
    writing_ = true;
    ws_.text(true);
    ws_.async_write(asio::buffer(*queue_.front()), [self = this->shared_from_this()](beast::error_code error, std::size_t) {
      self->writing_ = false;
      self->queue_.pop_front();  // the message just written: close() leaves it in place
      if (error || self->closed_) {
        self->close();
        return;
      }
      if (!self->queue_.empty()) self->write_next();
    });
  }

  void close() {
    if (closed_) return;
    closed_ = true;
    // A write still in flight reads from the front message and pops it when it completes.
    queue_.erase(writing_ ? std::next(queue_.begin()) : queue_.begin(), queue_.end());
    if (subscribed_) state().console.unsubscribe(subscription_);
    subscribed_ = false;
  }

  websocket::stream<Stream> ws_;
  std::unique_ptr<ConnectionCount> count_;
  beast::flat_buffer incoming_;
  std::deque<std::shared_ptr<const std::string>> queue_;
  bool writing_ = false;
  bool closed_ = false;
  bool subscribed_ = false;
  std::uint64_t subscription_ = 0;
};

template <class Stream>
class HttpSession : public std::enable_shared_from_this<HttpSession<Stream>> {
 public:
  HttpSession(Stream&& stream, std::unique_ptr<ConnectionCount> count)
      : stream_(std::move(stream)), count_(std::move(count)) {}
  ~HttpSession() { stop_waiting(); }
  HttpSession(const HttpSession&) = delete;
  HttpSession& operator=(const HttpSession&) = delete;

  void run() {
    start_waiting();
    if constexpr (std::is_same_v<Stream, TlsStream>) {
      set_timeout(stream_, state().limits.request_timeout);
      stream_.async_handshake(asio::ssl::stream_base::server, [self = this->shared_from_this()](beast::error_code error) {
        if (error) return;  // not TLS, or no certificate it trusts: closed
        self->read();
      });
    } else {
      read();
    }
  }

 private:
  State& state() { return *count_->state(); }

  // In the list of connections a new one may close at the cap, from the moment this one waits
  // for a request until it has one (the io thread only: no lock).
  void start_waiting() {
    if (waiting_) return;
    std::weak_ptr<HttpSession> weak = this->shared_from_this();
    waiting_ = state().waiting_for_request.insert(state().waiting_for_request.end(), [weak] {
      if (const auto self = weak.lock()) {
        self->waiting_.reset();  // the acceptor took this entry off the list
        beast::error_code ignored;
        beast::get_lowest_layer(self->stream_).socket().close(ignored);  // its read ends, aborted
      }
    });
  }
  void stop_waiting() {
    if (!waiting_ || !count_) return;
    state().waiting_for_request.erase(*waiting_);
    waiting_.reset();
  }

  void read() {
    start_waiting();
    parser_.emplace();
    parser_->header_limit(static_cast<std::uint32_t>(state().limits.max_header_bytes));
    parser_->body_limit(state().limits.max_body_bytes);
    set_timeout(stream_, state().limits.request_timeout);
    http::async_read(stream_, buffer_, *parser_, [self = this->shared_from_this()](beast::error_code error, std::size_t) {
      self->on_read(error);
    });
  }

  void on_read(beast::error_code error) {
    stop_waiting();
    if (error == http::error::end_of_stream || error == beast::error::timeout || error == asio::error::eof ||
        error == asio::error::connection_reset || error == asio::error::operation_aborted) {
      shutdown();
      return;
    }
    if (error == http::error::header_limit) return respond_error(431, "request header too large", 11);
    if (error == http::error::body_limit) return respond_error(413, "request body too large", 11);
    if (error) return respond_error(400, "not an HTTP/1.1 request this server reads", 11);
    auto request = parser_->release();
    // Before anything is served: a page of another site, or one reaching us under another name
    // (DNS rebinding), gets nothing, not even the page's files or /live.
    const auto header = [&request](http::field field) -> std::optional<std::string_view> {
      const auto it = request.find(field);
      if (it == request.end()) return std::nullopt;
      return std::string_view(it->value().data(), it->value().size());
    };
    if (const auto why = state().origins.refusal(header(http::field::host), header(http::field::origin))) {
      state().console.count_refused_origin();
      return respond_error(403, *why, request.version());
    }
    const std::string target(request.target());
    if (target.find('?') != std::string::npos || target.find('#') != std::string::npos) {
      return respond_error(400, "query strings are not used", request.version());
    }
    if (websocket::is_upgrade(request)) {
      if (target != "/live") return respond_error(404, "no WebSocket here (the live feed is /live)", request.version());
      if (state().live_sessions >= state().limits.max_live_sessions) {
        return respond_error(503, "too many live viewers (" + std::to_string(state().limits.max_live_sessions) + ")",
                             request.version());
      }
      std::make_shared<LiveSession<Stream>>(std::move(stream_), std::move(count_))->run(std::move(request));
      return;
    }
    const bool head = request.method() == http::verb::head;
    if (const auto file = state().files.find(target); file != state().files.end()) {
      if (request.method() != http::verb::get && !head) {
        return respond_error(405, "method not allowed here", request.version(), request.keep_alive());
      }
      return respond(200, file->second.content_type, file->second.body, request.version(), request.keep_alive(), head,
                     /*cacheable=*/true);
    }
    HttpRequest console_request;
    console_request.method = std::string(request.method_string());
    console_request.target = target;
    if (const auto it = request.find(http::field::authorization); it != request.end()) {
      console_request.authorization = std::string(it->value());
    }
    console_request.body = std::move(request.body());
    const unsigned version = request.version();
    const bool keep_alive = request.keep_alive();
    state().console.handle(console_request, [self = this->shared_from_this(), version, keep_alive, head](HttpAnswer answer) {
      self->respond(answer.status, answer.content_type, answer.body, version, keep_alive, head, false);
    });
  }

  void respond_error(unsigned status, const std::string& message, unsigned version, bool keep_alive = false) {
    std::string body = "{\"error\":\"" + message + "\"}";
    respond(status, "application/json", body, version, keep_alive, false, false);
  }

  void respond(unsigned status, const std::string& content_type, const std::string& body, unsigned version,
               bool keep_alive, bool head, bool cacheable) {
    auto response = std::make_shared<http::response<http::string_body>>(static_cast<http::status>(status), version);
    response->set(http::field::server, "netmc-server");
    response->set(http::field::content_type, content_type);
    response->set("X-Content-Type-Options", "nosniff");
    response->set("Content-Security-Policy",
                  "default-src 'self'; connect-src 'self' ws: wss:; img-src 'self' data:; frame-ancestors 'none'");
    response->set(http::field::cache_control, cacheable ? "max-age=300" : "no-store");
    response->keep_alive(keep_alive);
    if (head) {
      response->content_length(body.size());
    } else {
      response->body() = body;
      response->prepare_payload();
    }
    set_timeout(stream_, state().limits.request_timeout);
    http::async_write(stream_, *response, [self = this->shared_from_this(), response](beast::error_code error, std::size_t) {
      if (error || !response->keep_alive()) {
        self->shutdown();
        return;
      }
      self->read();
    });
  }

  void shutdown() {
    if constexpr (std::is_same_v<Stream, TlsStream>) {
      set_timeout(stream_, std::chrono::seconds(2));
      stream_.async_shutdown([self = this->shared_from_this()](beast::error_code) {});
    } else {
      beast::error_code ignored;
      stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    }
  }

  Stream stream_;
  std::unique_ptr<ConnectionCount> count_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::optional<std::list<std::function<void()>>::iterator> waiting_;
};

void accept(const std::shared_ptr<State>& state) {
  state->acceptor.async_accept(asio::make_strand(state->io), [state](beast::error_code error, tcp::socket socket) {
    if (state->stopped || error == asio::error::operation_aborted) return;
    if (!error) {
      bool room = state->connections < state->limits.max_connections;
      if (!room && !state->waiting_for_request.empty()) {
        // Full: the connection that has waited longest for a request makes room (it is counted
        // until its aborted read returns, so the count may pass the cap by those in closing).
        const auto close_oldest = std::move(state->waiting_for_request.front());
        state->waiting_for_request.pop_front();
        close_oldest();
        room = true;
      }
      if (!room) {
        beast::error_code ignored;
        socket.close(ignored);  // full of sessions that are not waiting: closed at once, nothing read
      } else {
        auto count = std::make_unique<ConnectionCount>(state);
        if (state->tls) {
          std::make_shared<HttpSession<TlsStream>>(TlsStream(std::move(socket), *state->tls), std::move(count))->run();
        } else {
          std::make_shared<HttpSession<PlainStream>>(PlainStream(std::move(socket)), std::move(count))->run();
        }
      }
    }
    accept(state);
  });
}

}  // namespace

HttpConsole::HttpConsole(asio::io_context& io, ConsoleService& console, const std::string& bind_address,
                         std::uint16_t port, RequestOriginPolicy origins, std::shared_ptr<asio::ssl::context> tls,
                         HttpConsoleLimits limits, const std::string& dygraphs_dir)
    : state_(std::make_shared<State>(io, console, std::move(origins), std::move(tls), limits)) {
  for (const auto& [target, name, type] :
       {std::tuple{"/", "index.html", "text/html; charset=utf-8"},
        std::tuple{"/index.html", "index.html", "text/html; charset=utf-8"},
        std::tuple{"/console.js", "console.js", "text/javascript; charset=utf-8"},
        std::tuple{"/console.css", "console.css", "text/css; charset=utf-8"}}) {
    state_->files[target] = State::StaticFile{type, std::string(console_asset(name))};
  }
  for (const auto& [name, type] : {std::pair{"dygraph.min.js", "text/javascript; charset=utf-8"},
                                   std::pair{"dygraph.min.css", "text/css; charset=utf-8"}}) {
    std::string body = read_bounded(dygraphs_dir + "/" + name);
    if (body.empty()) {
      spdlog::warn("console: {}/{} missing (Debian package libjs-dygraphs): the page shows no plots", dygraphs_dir,
                   name);
      continue;
    }
    state_->files[std::string("/javascript/dygraphs/") + name] = State::StaticFile{type, std::move(body)};
  }
  beast::error_code error;
  const auto address = asio::ip::make_address(bind_address, error);
  if (error) throw std::invalid_argument("--http: '" + bind_address + "' is not an IP address");
  const tcp::endpoint endpoint(address, port);
  state_->acceptor.open(endpoint.protocol(), error);
  if (!error) state_->acceptor.set_option(asio::socket_base::reuse_address(true), error);
  if (!error) state_->acceptor.bind(endpoint, error);
  if (!error) state_->acceptor.listen(asio::socket_base::max_listen_connections, error);
  if (error) {
    throw std::runtime_error("--http: cannot listen on " + bind_address + ":" + std::to_string(port) + ": " +
                             error.message());
  }
  port_ = state_->acceptor.local_endpoint().port();
  accept(state_);
}

HttpConsole::~HttpConsole() { stop(); }

void HttpConsole::stop() {
  if (state_->stopped) return;
  state_->stopped = true;
  beast::error_code ignored;
  state_->acceptor.close(ignored);
}

}  // namespace netmc::console
