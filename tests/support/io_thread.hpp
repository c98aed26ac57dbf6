#pragma once
// Runs an io_context on its own thread once there is work (start() after the server exists, or
// run() returns at once); waits for it with a bound so a hang fails instead of hanging. Declare
// it before everything that holds a Session, so the io_context outlives them.

#include <utility>  // before Asio: Boost 1.74 needs it

#include <boost/asio.hpp>

#include <chrono>
#include <future>

namespace netmc::test_support {

class IoThread {
 public:
  ~IoThread() { join(); }
  void start() { done_ = std::async(std::launch::async, [this] { io.run(); }); }
  // True when run() returned by itself (ran out of work) within `bound`.
  bool finishes_within(std::chrono::milliseconds bound) {
    return done_.wait_for(bound) == std::future_status::ready;
  }
  void join() {
    io.stop();
    if (done_.valid()) done_.get();
  }
  boost::asio::io_context io;

 private:
  std::future<void> done_;
};

}  // namespace netmc::test_support
