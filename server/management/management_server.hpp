#pragma once
// The management endpoint of netmc-server: accepts TCP connections and dispatches each framed
// Request to a handler on the io_context thread. Sessions may be answered from any thread.

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio.hpp>

#include <deque>
#include <functional>
#include <memory>
#include <string>

#include "idl/management.pb.h"
#include "server/management/frame_codec.hpp"

namespace netmc::management {

class Session : public std::enable_shared_from_this<Session> {
 public:
  using Dispatch = std::function<void(Session&, const netmc::v1::Request&)>;
  Session(boost::asio::ip::tcp::socket socket, Dispatch dispatch);

  void start();
  // Thread-safe; responses leave in the order they were sent.
  void send(const netmc::v1::Response& response);
  void close();

 private:
  void read();
  void write_next();

  boost::asio::ip::tcp::socket socket_;
  Dispatch dispatch_;
  FrameDecoder decoder_;
  std::array<char, 8192> buffer_{};
  std::deque<std::string> outbox_;
  bool closing_ = false;
};

class ManagementServer {
 public:
  struct Handler {
    Session::Dispatch on_request;
  };
  ManagementServer(boost::asio::io_context& io, const std::string& bind_address, std::uint16_t port,
                   Handler handler);
  std::uint16_t port() const;
  void stop();

 private:
  void accept();

  boost::asio::ip::tcp::acceptor acceptor_;
  Handler handler_;
};

}  // namespace netmc::management
