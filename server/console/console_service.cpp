#include "server/console/console_service.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <string_view>

#include "server/console/process_metrics.hpp"
#include "server/console/prometheus_text.hpp"
#include "server/drive/cia402.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::console {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxQueuedResponses = 4096;
constexpr std::chrono::seconds kSubmitTimeout{15};

json proto_json(const google::protobuf::Message& message) { return json::parse(job::to_json(message)); }

HttpAnswer json_answer(unsigned status, const json& body) {
  return HttpAnswer{status, "application/json", body.dump()};
}

HttpAnswer error_answer(unsigned status, const std::string& message) {
  return json_answer(status, json{{"error", message}});
}

// "123" -> 123; anything else (signs, spaces, 20+ digits) -> nullopt.
std::optional<std::uint64_t> parse_id(std::string_view text) {
  if (text.empty() || text.size() > 19) return std::nullopt;
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value == 0) return std::nullopt;
  return value;
}

}  // namespace

// The console's end of its conversation with the job service: responses queue here (from any
// thread) until the console's thread takes them; the oldest go first past the bound.
class ConsoleService::Peer final : public management::Peer {
 public:
  void send(const netmc::v1::Response& response) override {
    std::lock_guard lock(mutex_);
    if (queue_.size() >= kMaxQueuedResponses) queue_.pop_front();
    queue_.push_back(response);
  }
  bool open() const override { return open_.load(std::memory_order_acquire); }
  void hold() override {}
  void release() override {}
  std::string name() const override { return "console"; }

  std::deque<netmc::v1::Response> take() {
    std::lock_guard lock(mutex_);
    return std::exchange(queue_, {});
  }
  void close() { open_.store(false, std::memory_order_release); }

 private:
  std::mutex mutex_;
  std::deque<netmc::v1::Response> queue_;
  std::atomic<bool> open_{true};
};

ConsoleService::ConsoleService(boost::asio::io_context& io, service::JobService& jobs, ConsoleOptions options)
    : io_(io),
      jobs_(jobs),
      options_(std::move(options)),
      peer_(std::make_shared<Peer>()),
      state_timer_(io),
      live_timer_(io) {
  repeat(state_timer_, options_.state_period, &ConsoleService::tick_state);
  repeat(live_timer_, options_.live_period, &ConsoleService::tick_live);
}

ConsoleService::~ConsoleService() { stop(); }

void ConsoleService::stop() {
  if (stopped_) return;
  stopped_ = true;
  state_timer_.cancel();
  live_timer_.cancel();
  peer_->close();
  subscribers_.clear();
}

std::shared_ptr<sim::CycleListener> ConsoleService::live_cycles(std::uint64_t job_id) {
  auto feed = std::make_shared<LiveFeed>();
  std::lock_guard lock(feeds_mutex_);
  if (stopped_) return nullptr;
  feeds_[job_id] = feed;
  return feed;
}

std::uint64_t ConsoleService::subscribe(Subscriber subscriber) {
  const std::uint64_t id = next_subscriber_++;
  subscribers_.emplace(id, std::move(subscriber));
  return id;
}

void ConsoleService::unsubscribe(std::uint64_t id) { subscribers_.erase(id); }

std::string ConsoleService::hello() const {
  return json{{"type", "hello"}, {"version", options_.version}, {"token_required", options_.token_required}}.dump();
}

void ConsoleService::broadcast(std::string message) {
  const auto shared = std::make_shared<const std::string>(std::move(message));
  // A subscriber may unsubscribe itself while it is told (its socket failed).
  const auto subscribers = subscribers_;
  for (const auto& [id, subscriber] : subscribers) subscriber(shared);
}

netmc::v1::Response ConsoleService::ask(netmc::v1::Request request, bool admin) {
  const std::uint64_t id = next_request_++;
  request.set_request_id(id);
  jobs_.handle(peer_, request, admin);
  // Status, nodes and cancel are answered within handle(); anything else taken is dispatched.
  std::optional<netmc::v1::Response> mine;
  auto responses = peer_->take();
  std::deque<netmc::v1::Response> others;
  for (auto& response : responses) {
    if (!mine && response.request_id() == id) mine = std::move(response);
    else others.push_back(std::move(response));
  }
  for (const auto& response : others) peer_->send(response);  // back, in order, for take_responses
  if (!mine) {
    netmc::v1::Response none;
    none.set_request_id(id);
    none.mutable_error()->set_message("the job service did not answer");
    return none;
  }
  return *mine;
}

bool ConsoleService::add_iteration(JobView& view, const netmc::v1::IterationMetrics& metrics) {
  const bool known = std::any_of(view.iterations.begin(), view.iterations.end(),
                                 [&](const auto& m) { return m.iteration() == metrics.iteration(); });
  if (!known) view.iterations.push_back(metrics);
  return !known;
}

void ConsoleService::take_responses() {
  for (const auto& response : peer_->take()) {
    const std::uint64_t id = response.request_id();
    if (const auto pending = pending_submits_.find(id); pending != pending_submits_.end()) {
      if (response.has_accepted()) {
        pending->second(json_answer(202, json{{"job", response.accepted().job_id()}}));
      } else if (response.has_error()) {
        pending->second(error_answer(400, response.error().message()));
      } else {
        continue;  // a later update of the job it submitted: the watch shows those
      }
      pending_submits_.erase(pending);
      continue;
    }
    const auto watch = watches_.find(id);
    if (watch == watches_.end()) continue;
    const std::uint64_t job_id = watch->second;
    JobView& view = views_[job_id];
    if (response.has_status() && response.status().jobs_size() > 0) {
      view.status = response.status().jobs(0);
    } else if (response.has_iteration()) {
      const auto& metrics = response.iteration().metrics();
      if (add_iteration(view, metrics)) {
        broadcast(json{{"type", "iteration"}, {"job", job_id}, {"metrics", proto_json(metrics)}}.dump());
      }
    } else if (response.has_finished()) {
      view.finished = response.finished();
      view.status.set_state(response.finished().state());
      view.status.set_error(response.finished().error());
      // The status was taken before the last iteration ended; the end counts every one kept.
      view.status.set_iterations_done(std::max(view.status.iterations_done(),
                                               static_cast<std::uint32_t>(response.finished().result().iterations_size())));
      for (const auto& metrics : response.finished().result().iterations()) add_iteration(view, metrics);
      broadcast(json{{"type", "finished"}, {"job", job_id}, {"finished", proto_json(response.finished())}}.dump());
      watches_.erase(watch);
    } else if (response.has_error()) {
      watches_.erase(watch);  // the job is gone; the next state tick forgets it
    }
  }
}

void ConsoleService::repeat(boost::asio::steady_timer& timer, std::chrono::milliseconds period,
                            void (ConsoleService::*tick)()) {
  timer.expires_after(period);
  timer.async_wait([this, &timer, period, tick](const boost::system::error_code& error) {
    if (error || stopped_) return;
    (this->*tick)();
    repeat(timer, period, tick);
  });
}

netmc::v1::StatusReply ConsoleService::refresh_nodes_and_jobs() {
  netmc::v1::Request nodes;
  nodes.mutable_nodes();
  if (const auto answer = ask(nodes); answer.has_nodes()) nodes_ = answer.nodes();
  netmc::v1::Request status;
  status.mutable_status();
  return ask(status).status();
}

void ConsoleService::tick_state() {
  take_responses();
  const auto jobs = refresh_nodes_and_jobs();
  std::map<std::uint64_t, JobView> seen;
  for (const auto& job : jobs.jobs()) {
    JobView view;
    if (const auto it = views_.find(job.job_id()); it != views_.end()) view = std::move(it->second);
    if (!view.finished) view.status = job;
    seen.emplace(job.job_id(), std::move(view));
  }
  views_ = std::move(seen);
  // Every job that may still run is watched, so its iterations reach the page as they end.
  for (auto& [id, view] : views_) {
    const std::string& state = view.status.state();
    if (view.watch_request != 0 || view.finished || (state != "queued" && state != "running")) continue;
    netmc::v1::Request watch;
    view.watch_request = next_request_++;
    watch.set_request_id(view.watch_request);
    watch.mutable_watch()->set_job_id(id);
    watches_[view.watch_request] = id;
    jobs_.handle(peer_, watch);
  }
  take_responses();
  json message{{"type", "state"}, {"nodes", json::array()}, {"jobs", json::array()}};
  for (const auto& node : nodes_.nodes()) message["nodes"].push_back(proto_json(node));
  for (const auto& [id, view] : views_) message["jobs"].push_back(proto_json(view.status));
  broadcast(message.dump());
}

void ConsoleService::tick_live() {
  take_responses();
  std::map<std::uint64_t, std::shared_ptr<LiveFeed>> feeds;
  {
    std::lock_guard lock(feeds_mutex_);
    feeds = feeds_;
  }
  for (const auto& [job_id, feed] : feeds) {
    auto taken = feed->take();
    dropped_samples_ += taken.dropped;
    const auto view = views_.find(job_id);
    const bool ended = view != views_.end() && view->second.finished.has_value();
    if (taken.cycles.empty() && taken.dropped == 0) {
      if (ended) {
        std::lock_guard lock(feeds_mutex_);
        feeds_.erase(job_id);
      }
      continue;
    }
    const auto shown = decimate(taken.cycles, options_.samples_per_message);
    json samples = json::array();
    for (const auto& cycle : shown) {
      const auto pair = [](const control::AxisVector& v) {
        json out = json::array();
        for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(std::isfinite(v[i]) ? json(v[i]) : json());
        return out;
      };
      samples.push_back(json{{"t", cycle.time_s},
                             {"ref", pair(cycle.reference_m)},
                             {"pos", pair(cycle.position_m)},
                             {"e", std::isfinite(cycle.contour_error_m) ? json(cycle.contour_error_m) : json()},
                             {"u", pair(cycle.command)},
                             {"tau", cycle.latest_tau_s}});
    }
    const std::size_t iteration = shown.empty() ? 0 : shown.back().iteration;
    broadcast(json{{"type", "cycles"},
                   {"job", job_id},
                   {"iteration", iteration},
                   {"dropped", taken.dropped},
                   {"samples", std::move(samples)}}
                  .dump());
  }
}

std::optional<bool> ConsoleService::authorized(const HttpRequest& request) const {
  if (!options_.authorize) return std::nullopt;  // no token to show: the console only reads
  constexpr std::string_view kBearer = "Bearer ";
  if (request.authorization.rfind(kBearer, 0) != 0) return std::nullopt;
  return options_.authorize(request.authorization.substr(kBearer.size()));
}

HttpAnswer ConsoleService::state_answer() {
  const auto jobs = refresh_nodes_and_jobs();
  json body{{"version", options_.version},
            {"token_required", options_.token_required},
            {"nodes", json::array()},
            {"jobs", json::array()}};
  for (const auto& node : nodes_.nodes()) body["nodes"].push_back(proto_json(node));
  for (const auto& job : jobs.jobs()) body["jobs"].push_back(proto_json(job));
  return json_answer(200, body);
}

HttpAnswer ConsoleService::job_answer(std::uint64_t job_id) {
  take_responses();
  json body;
  const auto view = views_.find(job_id);
  if (view == views_.end()) {
    netmc::v1::Request status;
    status.mutable_status()->set_job_id(job_id);
    const auto answer = ask(status);
    if (answer.status().jobs_size() == 0) return error_answer(404, "no job " + std::to_string(job_id));
    body["status"] = proto_json(answer.status().jobs(0));
    body["iterations"] = json::array();
    return json_answer(200, body);
  }
  body["status"] = proto_json(view->second.status);
  body["iterations"] = json::array();
  auto iterations = view->second.iterations;
  std::sort(iterations.begin(), iterations.end(),
            [](const auto& a, const auto& b) { return a.iteration() < b.iteration(); });
  for (const auto& metrics : iterations) body["iterations"].push_back(proto_json(metrics));
  if (view->second.finished) {
    // The iterations are above; the rest of the end as the protocol has it.
    auto finished = *view->second.finished;
    finished.mutable_result()->clear_iterations();
    body["finished"] = proto_json(finished);
  }
  return json_answer(200, body);
}

void ConsoleService::submit(const HttpRequest& request, bool admin, std::function<void(HttpAnswer)> answer) {
  const json body = json::parse(request.body, nullptr, false);
  if (body.is_discarded() || !body.is_object()) {
    answer(error_answer(400, "body: expected a JSON object {\"preset\": NAME, ...}"));
    return;
  }
  for (const auto& [key, value] : body.items()) {
    if (key != "preset" && key != "controller" && key != "iterations" && key != "clock") {
      answer(error_answer(400, "body: unknown field '" + key.substr(0, 40) +
                                   "' (expected preset, controller, iterations, clock)"));
      return;
    }
  }
  const auto preset = body.find("preset");
  if (preset == body.end() || !preset->is_string() ||
      std::find(options_.presets.begin(), options_.presets.end(), preset->get<std::string>()) ==
          options_.presets.end()) {
    answer(error_answer(400, "preset: expected one of the names GET /api/presets lists"));
    return;
  }
  netmc::v1::JobSpec spec;
  try {
    spec = options_.preset_job(preset->get<std::string>());
  } catch (const std::exception& error) {
    answer(error_answer(400, std::string("preset: ") + error.what()));
    return;
  }
  if (const auto controller = body.find("controller"); controller != body.end()) {
    if (!controller->is_string() || controller->get<std::string>().empty() ||
        controller->get<std::string>().size() > 200) {
      answer(error_answer(400, "controller: expected a controller name (netmc sim --list-controllers)"));
      return;
    }
    spec.mutable_controller()->set_name(controller->get<std::string>());
  }
  if (const auto iterations = body.find("iterations"); iterations != body.end()) {
    if (!iterations->is_number_integer() || iterations->get<std::int64_t>() < 1 ||
        iterations->get<std::int64_t>() > 10000) {
      answer(error_answer(400, "iterations: expected a whole number in [1, 10000]"));
      return;
    }
    spec.set_iterations(static_cast<std::uint32_t>(iterations->get<std::int64_t>()));
  }
  if (const auto clock = body.find("clock"); clock != body.end()) {
    if (!clock->is_string() || (clock->get<std::string>() != "realtime" && clock->get<std::string>() != "lockstep")) {
      answer(error_answer(400, "clock: expected realtime or lockstep"));
      return;
    }
    spec.set_clock(clock->get<std::string>());
  }
  netmc::v1::Request submit;
  const std::uint64_t id = next_request_++;
  submit.set_request_id(id);
  *submit.mutable_submit()->mutable_spec() = spec;
  submit.mutable_submit()->set_keep_after_disconnect(true);
  pending_submits_[id] = std::move(answer);
  jobs_.handle(peer_, submit, admin);
  // The verdict comes from the job service's validation thread; a timer makes sure it is given.
  auto timer = std::make_shared<boost::asio::steady_timer>(io_, kSubmitTimeout);
  timer->async_wait([this, id, timer](const boost::system::error_code& error) {
    if (error || stopped_) return;
    take_responses();
    if (const auto pending = pending_submits_.find(id); pending != pending_submits_.end()) {
      pending->second(error_answer(504, "the job service gave no verdict on the job in time"));
      pending_submits_.erase(pending);
    }
  });
}

HttpAnswer ConsoleService::cancel(std::uint64_t job_id, bool admin) {
  netmc::v1::Request request;
  request.mutable_cancel()->set_job_id(job_id);
  const auto answer = ask(request, admin);
  if (answer.has_error()) {
    const bool missing = answer.error().message().rfind("cancel: no job", 0) == 0;
    return error_answer(missing ? 404 : 403, answer.error().message());
  }
  return json_answer(200, json{{"job", job_id}});
}

HttpAnswer ConsoleService::command_axis(const HttpRequest& request, bool admin) {
  const json body = json::parse(request.body, nullptr, false);
  if (body.is_discarded() || !body.is_object()) {
    return error_answer(400, "body: expected a JSON object {\"node\": NAME, \"axis\": NAME, \"kind\": KIND, ...}");
  }
  static const std::map<std::string, netmc::v1::AxisCommand::Kind> kinds{
      {"enable", netmc::v1::AxisCommand::ENABLE}, {"disable", netmc::v1::AxisCommand::DISABLE},
      {"quick-stop", netmc::v1::AxisCommand::QUICK_STOP}, {"move", netmc::v1::AxisCommand::MOVE},
      {"jog", netmc::v1::AxisCommand::JOG}};
  netmc::v1::Request request_to_server;
  auto& command = *request_to_server.mutable_axis_command();
  for (const auto& [key, value] : body.items()) {
    if (key == "node" || key == "axis") {
      if (!value.is_string() || value.get<std::string>().size() > 64) {
        return error_answer(400, key + ": expected a name of at most 64 characters");
      }
      (key == "node" ? command.mutable_node() : command.mutable_axis())->assign(value.get<std::string>());
    } else if (key == "kind") {
      const auto kind = value.is_string() ? kinds.find(value.get<std::string>()) : kinds.end();
      if (kind == kinds.end()) return error_answer(400, "kind: expected enable, disable, quick-stop, move or jog");
      command.set_kind(kind->second);
    } else if (key == "target_m" || key == "speed_m_s") {
      if (!value.is_number() || !std::isfinite(value.get<double>())) {
        return error_answer(400, key + ": expected a finite number");
      }
      key == "target_m" ? command.set_target_m(value.get<double>()) : command.set_speed_m_s(value.get<double>());
    } else {
      return error_answer(400, "body: unknown field '" + key.substr(0, 40) +
                                   "' (expected node, axis, kind, target_m, speed_m_s)");
    }
  }
  if (command.node().empty() || command.kind() == netmc::v1::AxisCommand::KIND_UNSPECIFIED) {
    return error_answer(400, "body: node and kind are required");
  }
  const auto answer = ask(request_to_server, admin);
  if (answer.has_error()) return error_answer(409, answer.error().message());
  return json_answer(200, json{{"command_number", answer.axis_command().command_number()}});
}

std::optional<bool> ConsoleService::change_permitted(const HttpRequest& request, const char* action,
                                                     const std::function<void(HttpAnswer)>& answer) const {
  // A console whose server asks for no token changes nothing: anyone who reaches it could.
  if (!options_.authorize) {
    answer(error_answer(403, "this console is read-only: its server asks for no token (start netmc-server with "
                             "--token-file to start and cancel jobs here)"));
    return std::nullopt;
  }
  const auto admin = authorized(request);
  if (!admin) answer(error_answer(401, std::string(action) + " needs the server's token (Authorization: Bearer TOKEN)"));
  return admin;
}

void ConsoleService::handle(const HttpRequest& request, std::function<void(HttpAnswer)> answer) {
  const std::string_view target = request.target;
  const bool get = request.method == "GET" || request.method == "HEAD";
  const bool post = request.method == "POST";
  const auto only = [&](bool allowed) {
    if (!allowed) answer(error_answer(405, "method " + request.method.substr(0, 16) + " not allowed here"));
    return allowed;
  };
  if (target == "/metrics") {
    if (!only(get)) return;
    answer(HttpAnswer{200, std::string(kPrometheusContentType), metrics_page()});
    return;
  }
  if (target == "/api/state") {
    if (only(get)) answer(state_answer());
    return;
  }
  if (target == "/api/presets") {
    if (only(get)) answer(json_answer(200, json{{"presets", options_.presets}}));
    return;
  }
  if (target == "/api/jobs") {
    if (!only(post)) return;
    const auto admin = change_permitted(request, "starting a job", answer);
    if (!admin) return;
    submit(request, *admin, std::move(answer));
    return;
  }
  if (target == "/api/axis-command") {
    if (!only(post)) return;
    const auto admin = change_permitted(request, "commanding an axis", answer);
    if (!admin) return;
    answer(command_axis(request, *admin));
    return;
  }
  constexpr std::string_view kJobs = "/api/jobs/";
  if (target.rfind(kJobs, 0) == 0) {
    std::string_view rest = target.substr(kJobs.size());
    constexpr std::string_view kCancel = "/cancel";
    const bool cancelling = rest.size() > kCancel.size() && rest.ends_with(kCancel);
    if (cancelling) rest.remove_suffix(kCancel.size());
    const auto id = parse_id(rest);
    if (!id) {
      answer(error_answer(404, "no such route"));
      return;
    }
    if (!cancelling) {
      if (only(get)) answer(job_answer(*id));
      return;
    }
    if (!only(post)) return;
    const auto admin = change_permitted(request, "cancelling a job", answer);
    if (!admin) return;
    answer(cancel(*id, *admin));
    return;
  }
  answer(error_answer(404, "no such route"));
}

std::string ConsoleService::metrics_page() {
  const auto totals = jobs_.totals();
  PrometheusPage page;
  page.family("netmc_nodes_up", MetricType::gauge, "Axis nodes heard from within the expiry.");
  page.sample(static_cast<double>(nodes_.nodes_size()));
  // A node that left reads 0 (its series does not vanish), for as long as this server runs.
  std::set<std::string> listed;
  for (const auto& node : nodes_.nodes()) {
    listed.insert(node.node());
    if (known_nodes_.size() < kMaxKnownNodes) known_nodes_.insert(node.node());
  }
  page.family("netmc_node_up", MetricType::gauge, "1 for each axis node the server lists, 0 for one that left.");
  for (const auto& name : known_nodes_) page.sample({{"node", name}}, listed.contains(name) ? 1.0 : 0.0);
  page.family("netmc_axis_fault", MetricType::gauge, "1 if the axis's drive has a latched fault (netmc reset clears it).");
  for (const auto& node : nodes_.nodes()) {
    for (const auto& drive : node.drives()) {
      page.sample({{"node", node.node()}, {"axis", drive.axis()}}, drive.fault_latched() ? 1.0 : 0.0);
    }
  }
  // One series per CiA 402 state, 1 for the drive's: a state change moves a value, not a series.
  page.family("netmc_axis_state", MetricType::gauge, "1 for the CiA 402 state the axis's drive reports, 0 for the others.");
  for (const auto& node : nodes_.nodes()) {
    for (const auto& drive : node.drives()) {
      for (int s = 0; s <= static_cast<int>(drive::PowerState::fault); ++s) {
        const std::string name = drive::power_state_name(static_cast<drive::PowerState>(s));
        page.sample({{"node", node.node()}, {"axis", drive.axis()}, {"state", name}}, drive.state() == name ? 1.0 : 0.0);
      }
    }
  }
  // Counted by the server from the nodes' reports (edges between them), kept when a node leaves.
  page.family("netmc_axis_trips_total", MetricType::counter,
              "Faults latched on the axis (its drive tripped) since this server first heard of it.");
  for (const auto& node : nodes_.nodes()) {
    for (const auto& drive : node.drives()) {
      page.sample({{"node", node.node()}, {"axis", drive.axis()}}, static_cast<double>(drive.trips()));
    }
  }
  page.family("netmc_axis_quick_stops_total", MetricType::counter,
              "Entries into Quick stop active seen in the node's reports (every 0.5 s).");
  for (const auto& node : nodes_.nodes()) {
    for (const auto& drive : node.drives()) {
      page.sample({{"node", node.node()}, {"axis", drive.axis()}}, static_cast<double>(drive.quick_stops()));
    }
  }
  // The node's clock as this server measures it (two-way time transfer), where it has.
  page.family("netmc_node_clock_offset_seconds", MetricType::gauge, "The node's clock minus the server's.");
  for (const auto& node : nodes_.nodes()) {
    if (node.clock_measured()) page.sample({{"node", node.node()}}, node.clock_offset_s());
  }
  page.family("netmc_node_round_trip_seconds", MetricType::gauge,
              "Round trip of the clock probe the offset was taken from (the offset is good to half of it).");
  for (const auto& node : nodes_.nodes()) {
    if (node.clock_measured()) page.sample({{"node", node.node()}}, node.round_trip_s());
  }
  // Two gauges, not an iteration label: a new iteration moves a value, not a series.
  page.family("netmc_job_last_e_max_meters", MetricType::gauge, "Largest contour error of the job's latest iteration.");
  for (const auto& last : totals.last_iterations) {
    page.sample({{"job", std::to_string(last.job_id)}, {"label", last.label}}, last.e_max_m);
  }
  page.family("netmc_job_last_iteration", MetricType::gauge, "The job's latest iteration (1-based).");
  for (const auto& last : totals.last_iterations) {
    page.sample({{"job", std::to_string(last.job_id)}, {"label", last.label}}, static_cast<double>(last.iteration));
  }
  page.family("netmc_jobs", MetricType::gauge, "Jobs the server holds, by state (ended ones while in its history).");
  for (const char* state : {"queued", "running", "done", "failed", "cancelled"}) {
    const auto it = totals.jobs_by_state.find(state);
    page.sample({{"state", state}}, it == totals.jobs_by_state.end() ? 0.0 : static_cast<double>(it->second));
  }
  const auto counter = [&](const char* name, const char* help, std::uint64_t value) {
    page.family(name, MetricType::counter, help);
    page.sample(static_cast<double>(value));
  };
  counter("netmc_iterations_total", "Iterations ended since the server started.", totals.iterations);
  counter("netmc_iterations_failed_total",
          "Iterations a job failed during: they never ended, and are in none of the counts below.",
          totals.failed_iterations);
  counter("netmc_deadline_misses_total", "Cycles computed after their deadline.", totals.deadline_misses);
  counter("netmc_feedback_lost_total", "Feedback samples lost on the uplink.", totals.lost_feedback);
  counter("netmc_setpoints_lost_total", "Setpoints lost on the downlink.", totals.lost_setpoints);
  counter("netmc_forged_samples_dropped_total",
          "Feedback or axis events dropped: from participants that do not host the axis.", totals.forged_samples);
  page.family("netmc_loop_delay_seconds", MetricType::summary,
              "Loop delay tau (feedback sampled to setpoint applied): quantiles of the latest iteration.");
  page.sample({{"quantile", "0.5"}}, totals.tau_p50_s);
  page.sample({{"quantile", "0.99"}}, totals.tau_p99_s);
  page.sample({{"quantile", "1"}}, totals.tau_max_s);
  page.sample({}, totals.tau_sum_s, "_sum");
  page.sample({}, static_cast<double>(totals.tau_count), "_count");
  if (options_.management_connections) {
    page.family("netmc_management_connections", MetricType::gauge, "Open management connections.");
    page.sample(static_cast<double>(options_.management_connections()));
  }
  page.family("netmc_console_connections", MetricType::gauge, "Open console connections (HTTP and WebSocket).");
  page.sample(static_cast<double>(console_connections_));
  counter("netmc_console_messages_dropped_total", "Live messages dropped for browsers that read too slowly.",
          dropped_messages_);
  counter("netmc_console_requests_refused_total",
          "Console requests refused for their Host or Origin (another site, or another name: 403).",
          refused_origins_);
  counter("netmc_console_samples_dropped_total", "Cycles the live feed let go (its reader behind, or busy).",
          dropped_samples_);
  page.family("netmc_build_info", MetricType::gauge, "1, with the server's version.");
  page.sample({{"version", options_.version}}, 1.0);
  if (const auto process = read_process_metrics()) {
    page.family("process_cpu_seconds_total", MetricType::counter, "User and system CPU time of the server.");
    page.sample(process->cpu_seconds);
    const auto gauge = [&page](const char* name, const char* help, double value) {
      page.family(name, MetricType::gauge, help);
      page.sample(value);
    };
    gauge("process_resident_memory_bytes", "Resident memory of the server.", process->resident_bytes);
    gauge("process_virtual_memory_bytes", "Virtual memory of the server.", process->virtual_bytes);
    gauge("process_start_time_seconds", "When the server started (Unix time).", process->start_time_unix_s);
    gauge("process_open_fds", "Open file descriptors.", process->open_fds);
    gauge("process_max_fds", "The limit of open file descriptors.", process->max_fds);
  }
  return page.text();
}

}  // namespace netmc::console
