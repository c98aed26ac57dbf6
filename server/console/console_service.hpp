#pragma once
// The lab console's model, transport aside (http_console.hpp carries it over HTTP and WebSocket;
// docs/operations/console.md is the contract). It is a client of the job service inside the
// server, with a management::Peer of its own: it lists nodes and jobs, watches every job it sees
// running, submits and cancels jobs for a browser that shows the token, gathers each running
// job's cycles from its LiveFeed, and writes /metrics.
//
// Threads: everything here runs on the io_context's one thread, except live_cycles() (a job's
// thread, when it starts) and the peer's send() (any thread); both only take a lock of their own
// for a moment, never the job service's.

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio.hpp>

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "idl/job.pb.h"
#include "idl/management.pb.h"
#include "server/console/live_feed.hpp"
#include "server/management/peer.hpp"
#include "server/service/job_service.hpp"

namespace netmc::console {

struct HttpRequest {
  std::string method;         // "GET", "POST", ...
  std::string target;         // "/api/jobs/3/cancel" (query strings are refused)
  std::string authorization;  // the Authorization header's value
  std::string body;
};

struct HttpAnswer {
  unsigned status = 200;
  std::string content_type = "application/json";
  std::string body;
};

struct ConsoleOptions {
  std::string version;
  // Who may change things: nullopt refuses the token; otherwise whether it is the admin's. Unset:
  // the server asks for no token, and the console is read-only (403 to every change).
  std::function<std::optional<bool>(const std::string& token)> authorize;
  bool token_required = false;
  // A job of a preset (its first run) and the presets' names (netmc's own presets).
  std::function<netmc::v1::JobSpec(const std::string& preset)> preset_job;
  std::vector<std::string> presets;
  // Open management connections (read on the io thread); unset: not reported.
  std::function<std::size_t()> management_connections;
  std::chrono::milliseconds state_period{500};
  std::chrono::milliseconds live_period{100};
  std::size_t samples_per_message = 50;
};

class ConsoleService {
 public:
  ConsoleService(boost::asio::io_context& io, service::JobService& jobs, ConsoleOptions options);
  ~ConsoleService();
  ConsoleService(const ConsoleService&) = delete;
  ConsoleService& operator=(const ConsoleService&) = delete;

  // The job service's live_cycles hook (JobServiceOptions): a feed per running job.
  std::shared_ptr<sim::CycleListener> live_cycles(std::uint64_t job_id);

  // Answers a request of the page (not a static file); `answer` may be called later (a submit
  // waits for the job service's validation), always on the io thread.
  void handle(const HttpRequest& request, std::function<void(HttpAnswer)> answer);

  // The live feed's messages go to every subscriber (the WebSocket sessions); the hello message
  // a new subscriber gets first.
  using Subscriber = std::function<void(const std::shared_ptr<const std::string>& message)>;
  std::uint64_t subscribe(Subscriber subscriber);
  void unsubscribe(std::uint64_t id);
  std::string hello() const;

  // The console's own counters, for /metrics and the tests.
  void count_connection(int delta) { console_connections_ += delta; }
  void count_dropped_messages(std::uint64_t n) { dropped_messages_ += n; }
  void count_refused_origin() { ++refused_origins_; }
  std::string metrics_page();

  void stop();

 private:
  class Peer;
  struct JobView {
    netmc::v1::JobStatus status;
    std::vector<netmc::v1::IterationMetrics> iterations;
    std::optional<netmc::v1::JobFinished> finished;
    std::uint64_t watch_request = 0;  // 0: not watched yet
  };

  void tick_state();
  void tick_live();
  // Calls `tick` every `period` on the io thread until stop().
  void repeat(boost::asio::steady_timer& timer, std::chrono::milliseconds period, void (ConsoleService::*tick)());
  // Asks the job service for the nodes (kept in nodes_) and the jobs (returned).
  netmc::v1::StatusReply refresh_nodes_and_jobs();
  // Adds `metrics` to the view unless that iteration is there already; true if it was new.
  static bool add_iteration(JobView& view, const netmc::v1::IterationMetrics& metrics);
  // A request the job service answers at once (status, nodes, cancel); its response.
  netmc::v1::Response ask(netmc::v1::Request request, bool admin = false);
  // What the peer received since the last call, each to its place.
  void take_responses();
  void broadcast(std::string message);

  HttpAnswer state_answer();
  HttpAnswer job_answer(std::uint64_t job_id);
  void submit(const HttpRequest& request, bool admin, std::function<void(HttpAnswer)> answer);
  HttpAnswer cancel(std::uint64_t job_id, bool admin);
  // POST /api/axis-command: an operator's commissioning command, as netmc enable ... jog send it.
  HttpAnswer command_axis(const HttpRequest& request, bool admin);
  // The token's verdict: nullopt: refused (answer 401); else admin or not.
  std::optional<bool> authorized(const HttpRequest& request) const;
  // authorized(), answering the refusal itself: 403 on a console without a token (read-only),
  // 401 naming `action` ("starting a job") without a valid one.
  std::optional<bool> change_permitted(const HttpRequest& request, const char* action,
                                       const std::function<void(HttpAnswer)>& answer) const;

  boost::asio::io_context& io_;
  service::JobService& jobs_;
  ConsoleOptions options_;
  std::shared_ptr<Peer> peer_;
  boost::asio::steady_timer state_timer_;
  boost::asio::steady_timer live_timer_;
  std::uint64_t next_request_ = 1;
  std::map<std::uint64_t, std::function<void(HttpAnswer)>> pending_submits_;  // by request id
  std::map<std::uint64_t, std::uint64_t> watches_;                            // request id -> job id
  std::map<std::uint64_t, JobView> views_;                                    // by job id
  netmc::v1::NodesReply nodes_;
  std::map<std::uint64_t, Subscriber> subscribers_;
  std::uint64_t next_subscriber_ = 1;
  std::mutex feeds_mutex_;
  std::map<std::uint64_t, std::shared_ptr<LiveFeed>> feeds_;  // by job id, under feeds_mutex_
  std::int64_t console_connections_ = 0;
  std::uint64_t dropped_messages_ = 0;
  std::uint64_t refused_origins_ = 0;
  // Every node /metrics has listed (netmc_node_up reads 0 for one that left); bounded.
  std::set<std::string> known_nodes_;
  static constexpr std::size_t kMaxKnownNodes = 1024;
  std::uint64_t dropped_samples_ = 0;
  bool stopped_ = false;
};

}  // namespace netmc::console
