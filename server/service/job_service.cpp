#include "server/service/job_service.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "dds_typesPubSubTypes.h"
#include "server/dds/topics.hpp"
#include "server/job/job_builder.hpp"
#include "server/realtime/realtime_scheduling.hpp"
#include "server/service/job_admission.hpp"
#include "server/service/lockstep_dds_runner.hpp"
#include "server/service/realtime_dds_runner.hpp"

namespace netmc::service {
namespace {

double unix_now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

netmc::v1::Response error_response(std::uint64_t request_id, const std::string& message) {
  netmc::v1::Response response;
  response.set_request_id(request_id);
  response.mutable_error()->set_message(message);
  return response;
}

const char* health_name(netmc::dds::NodeHealth health) {
  switch (health) {
    case netmc::dds::NODE_IDLE: return "idle";
    case netmc::dds::NODE_RUNNING: return "running";
    case netmc::dds::NODE_HOLD: return "hold";
    case netmc::dds::NODE_FAULT: return "fault";
    case netmc::dds::NODE_REFUSED: return "refused";
    case netmc::dds::NODE_LEAVING: return "leaving";
  }
  return "unknown";
}

}  // namespace

JobService::JobService(dds::DdsContext& context, NodeDirectory& nodes, ClockTracker& clocks,
                       JobServiceOptions options)
    : context_(context),
      nodes_(nodes),
      clocks_(clocks),
      options_(options),
      control_(context.writer(context.topic<netmc::dds::JobControlPubSubType>(dds::kJobControlTopic),
                              dds::Delivery::control)),
      iteration_logs_(context.writer(
          context.topic<netmc::dds::IterationLogPubSubType>(dds::kIterationLogTopic),
          dds::Delivery::log)),
      scheduler_([this] { schedule(); }),
      validator_([this] { validate(); }) {
  if (options_.store) {
    std::lock_guard lock(mutex_);
    restore_from_store();
    wake_.notify_all();
  }
}

JobService::~JobService() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    for (auto& [id, job] : jobs_) {
      job->cancel_reason = "the server is shutting down";
      job->cancel.store(true);
    }
  }
  wake_.notify_all();
  validator_.join();
  scheduler_.join();  // it joins every job thread before it returns
  // The writes of the jobs' ends, and what follows them (answers to clients), refer to this.
  if (options_.store) options_.store->flush();
}

void JobService::handle(const std::shared_ptr<management::Peer>& session,
                        const netmc::v1::Request& request, bool admin) {
  netmc::v1::Response response;
  response.set_request_id(request.request_id());
  switch (request.kind_case()) {
    case netmc::v1::Request::kSubmit: {
      const std::size_t spec_bytes = request.submit().spec().ByteSizeLong();
      std::lock_guard lock(mutex_);
      if (queue_.size() + submissions_.size() >= options_.max_queued_jobs) {
        session->send(error_response(request.request_id(), "submit: the server's queue is full (" +
                                                               std::to_string(options_.max_queued_jobs) +
                                                               " jobs waiting); try again later"));
        return;
      }
      if (queued_spec_bytes_ + spec_bytes > options_.max_queued_spec_bytes) {
        session->send(error_response(
            request.request_id(),
            fmt::format("submit: the jobs waiting hold {:.1f} MiB of specs and this one {:.1f} MiB, beyond the "
                        "server's {:.0f} MiB; try again when the queue is shorter",
                        static_cast<double>(queued_spec_bytes_) / 1048576.0, static_cast<double>(spec_bytes) / 1048576.0,
                        static_cast<double>(options_.max_queued_spec_bytes) / 1048576.0)));
        return;
      }
      queued_spec_bytes_ += spec_bytes;
      submissions_.push_back({session, request});
      wake_.notify_all();
      return;
    }
    case netmc::v1::Request::kCancel: {
      std::lock_guard lock(mutex_);
      const auto it = jobs_.find(request.cancel().job_id());
      if (it == jobs_.end()) {
        session->send(error_response(request.request_id(),
                                     "cancel: no job " + std::to_string(request.cancel().job_id())));
        return;
      }
      if (!admin && it->second->session.lock() != session) {
        session->send(error_response(request.request_id(), "cancel: job " + std::to_string(it->first) +
                                                               " was submitted on another connection; only it, "
                                                               "or a client with the server's admin token, may cancel "
                                                               "the job (netmc-server --admin-token-file FILE; the "
                                                               "client names FILE in NETMC_TOKEN_FILE)"));
        return;
      }
      Job& job = *it->second;
      job.cancel_reason = admin && job.session.lock() != session ? "cancelled by an admin (netmc cancel)"
                                                                 : "cancelled by its client";
      job.cancel.store(true);
      // A queued job leaves the queue now, not when the job ahead of it ends.
      if (const auto queued = std::find(queue_.begin(), queue_.end(), it->second); queued != queue_.end()) {
        queue_.erase(queued);
        end_queued(job, job.cancel_reason);
        spdlog::info("job {} cancelled while queued", job.id);
        wake_.notify_all();
      }
      *response.mutable_status()->add_jobs() = job.status;
      break;
    }
    case netmc::v1::Request::kStatus: {
      std::lock_guard lock(mutex_);
      for (const auto& [id, job] : jobs_) {
        if (request.status().job_id() == 0 || request.status().job_id() == id) {
          *response.mutable_status()->add_jobs() = job->status;
        }
      }
      break;
    }
    case netmc::v1::Request::kWatch: {
      std::lock_guard lock(mutex_);
      const auto it = jobs_.find(request.watch().job_id());
      if (it == jobs_.end()) {
        session->send(error_response(request.request_id(),
                                     "watch: no job " + std::to_string(request.watch().job_id()) +
                                         " (never submitted, or ended more than " +
                                         std::to_string(options_.job_history) +
                                         " jobs ago: netmc jobs lists the server's history)"));
        return;
      }
      start_watch(*it->second, session, request.request_id());
      return;
    }
    case netmc::v1::Request::kNodes: {
      const auto now = std::chrono::steady_clock::now();
      auto& reply = *response.mutable_nodes();
      reply.set_server(context_.identity());
      reply.set_expiry_s(std::chrono::duration<double>(nodes_.expiry()).count());
      for (const auto& record : nodes_.nodes()) fill_node_info(record, now, *reply.add_nodes());
      break;
    }
    case netmc::v1::Request::kReset: {
      const auto& reset = request.reset();
      if (!admin && options_.admin_token_configured) {
        session->send(error_response(request.request_id(),
                                     "reset: needs the admin token (the file of netmc-server --admin-token-file, "
                                     "named to the client by NETMC_TOKEN_FILE)"));
        return;
      }
      std::optional<NodeRecord> target;
      for (auto& record : nodes_.nodes()) {
        if (record.status.node() == reset.node()) target = std::move(record);
      }
      if (!target) {
        session->send(error_response(request.request_id(), "reset: no node '" + reset.node().substr(0, 64) +
                                                               "' (netmc nodes lists the nodes this server sees)"));
        return;
      }
      std::vector<std::string> axes(reset.axes().begin(), reset.axes().end());
      for (const auto& axis : axes) {
        const auto& hosted = target->status.axes();
        if (std::find(hosted.begin(), hosted.end(), axis) == hosted.end()) {
          session->send(error_response(request.request_id(), "reset: node " + reset.node() + " hosts no axis '" +
                                                                 axis.substr(0, 64) + "'"));
          return;
        }
      }
      if (axes.empty()) axes.assign(target->status.axes().begin(), target->status.axes().end());
      try {
        for (const auto& axis : axes) {
          netmc::dds::JobControl control;
          control.axis(axis);
          control.server(context_.identity());
          control.kind(netmc::dds::CONTROL_FAULT_RESET);
          dds::write_checked(control_, &control);
        }
      } catch (const std::exception& error) {
        session->send(error_response(request.request_id(), std::string("reset: ") + error.what()));
        return;
      }
      spdlog::info("fault reset of node {} ({} axes) sent{}", reset.node(), axes.size(), admin ? " by an admin" : "");
      auto& reply = *response.mutable_reset();
      reply.set_server(context_.identity());
      reply.set_expiry_s(std::chrono::duration<double>(nodes_.expiry()).count());
      fill_node_info(*target, std::chrono::steady_clock::now(), *reply.add_nodes());
      break;
    }
    case netmc::v1::Request::kJobs:
      try {
        *response.mutable_jobs() = list_jobs(request.jobs());
      } catch (const std::exception& error) {
        session->send(error_response(request.request_id(), std::string("jobs: ") + error.what()));
        return;
      }
      break;
    case netmc::v1::Request::KIND_NOT_SET:
      session->send(error_response(request.request_id(),
                                   "request: empty (expected submit, cancel, status, watch, nodes, reset or jobs)"));
      return;
  }
  session->send(response);
}

ServiceTotals JobService::totals() const {
  std::lock_guard lock(mutex_);
  ServiceTotals totals = totals_;
  for (const auto& [id, job] : jobs_) ++totals.jobs_by_state[job->status.state()];
  return totals;
}

void JobService::fill_node_info(const NodeRecord& record, std::chrono::steady_clock::time_point now,
                                netmc::v1::NodeInfo& info) const {
  info.set_node(record.status.node());
  for (const auto& axis : record.status.axes()) info.add_axes(axis);
  info.set_plant(record.status.plant());
  const std::string health = record.refused.empty() ? health_name(record.status.health()) : "refused";
  const std::string detail = record.refused.empty() ? record.status.detail() : record.refused;
  info.set_health(health + (detail.empty() ? "" : ": " + detail));
  info.set_last_seen_s(std::chrono::duration<double>(now - record.last_seen).count());
  info.set_clock(record.status.clock());
  info.set_time_base(record.status.time_base());
  info.set_participant(record.status.participant());
  std::string holders;
  for (const auto& hold : record.status.holds()) {
    holders += (holders.empty() ? "" : ", ") + hold.server() + " (job " + std::to_string(hold.job_id()) + ", axis " +
               hold.axis() + ")";
  }
  info.set_held_by(holders);
  if (const auto clock = clocks_.estimate(record.status.node())) {
    info.set_clock_measured(true);
    info.set_clock_offset_s(clock->offset_s);
    info.set_round_trip_s(clock->round_trip_s);
  }
  for (const auto& drive : record.status.drives()) {
    auto& entry = *info.add_drives();
    entry.set_axis(drive.axis());
    entry.set_drive(drive.drive());
    entry.set_state(drive.state());
    entry.set_statusword(drive.statusword());
    entry.set_error_code(drive.error_code());
    entry.set_fault_latched(drive.fault_latched());
    entry.set_last_fault(drive.last_fault());
    entry.set_limits(drive.limits());
  }
  info.set_server_name(record.status.server_name());
}

void JobService::validate() {
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || !submissions_.empty(); });
    if (stopping_) return;
    const Submission submission = std::move(submissions_.front());
    submissions_.pop_front();
    lock.unlock();
    admit(submission);  // the spec is checked (and its work bounded) off the I/O thread
    lock.lock();
  }
}

void JobService::admit(const Submission& submission) {
  const auto& request = submission.request;
  const auto& session = submission.session;
  netmc::v1::JobSpec spec = request.submit().spec();
  const std::size_t spec_bytes = spec.ByteSizeLong();  // as handle() counted it
  const auto refuse = [&](const std::string& message) {
    {
      std::lock_guard lock(mutex_);
      queued_spec_bytes_ -= spec_bytes;
    }
    session->send(error_response(request.request_id(), message));
  };
  job::apply_defaults(spec);
  try {
    job::reject_file_references(spec);  // the server opens no path a client names
    job::build_contour_job(spec, options_.build_options());  // every field checked before the job is queued
  } catch (const std::exception& error) {
    refuse(error.what());
    return;
  }
  // The axes get the spec in one DDS sample: a larger one would fail when the job starts.
  if (const std::size_t bytes = spec.ByteSizeLong(); bytes > netmc::dds::kMaxJobSpec) {
    refuse(fmt::format("submit: the job spec takes {} bytes, more than the {} its axis nodes take (an inline delay "
                       "trace of 1 000 000 samples alone takes 8 MB: shorten it to about 500 000)",
                       bytes, netmc::dds::kMaxJobSpec));
    return;
  }
  auto job = std::make_shared<Job>();
  job->axes = job::axis_names(spec);
  job->spec = spec;
  job->spec_bytes = spec_bytes;
  job->session = session;
  job->request_id = request.request_id();
  job->keep_after_disconnect = request.submit().keep_after_disconnect();
  job->owner = session->name();
  job->accepted_unix_s = unix_now_s();
  const std::string label = spec.name().empty() ? spec.controller().name() : spec.name();
  std::uint64_t stored_id = 0;
  if (options_.store) {
    // Accepted only once on disk: a crash after the client hears "accepted" loses nothing.
    store::StoredJob stored;
    stored.label = label;
    stored.owner = job->owner;
    stored.spec = spec.SerializeAsString();
    stored.iterations_total = spec.iterations();
    stored.keep_after_disconnect = job->keep_after_disconnect;
    try {
      stored_id = options_.store->accept(stored);
    } catch (const store::StoreError& error) {
      refuse(std::string("submit: not accepted: ") + error.what() +
             "; the server accepts no job until its job store can be written (--state-dir)");
      return;
    }
  }
  std::lock_guard lock(mutex_);
  if (stopping_) return;
  job->id = options_.store ? stored_id : next_id_++;
  job->status.set_job_id(job->id);
  job->status.set_state("queued");
  job->status.set_iterations_total(spec.iterations());
  job->status.set_label(label);
  jobs_[job->id] = job;
  session->hold();  // not idle while its job is queued or running
  // Acknowledge before the worker can see the job, so "accepted" precedes its updates.
  netmc::v1::Response response;
  response.set_request_id(request.request_id());
  response.mutable_accepted()->set_job_id(job->id);
  session->send(response);
  queue_.push_back(job);
  spdlog::info("job {} accepted: {}, {} iterations on axes {}", job->id, job->status.label(), spec.iterations(),
               fmt::join(job->axes, ","));
  wake_.notify_all();
}

void JobService::tend_jobs() {
  const auto gone = [](const Job& job) {
    const auto session = job.session.lock();
    return !job.keep_after_disconnect && (!session || !session->open());
  };
  for (auto it = queue_.begin(); it != queue_.end();) {
    Job& job = **it;
    if (!gone(job)) {
      ++it;
      continue;
    }
    spdlog::info("job {} dropped from the queue: its client disconnected", job.id);
    end_queued(job, "its client disconnected");
    it = queue_.erase(it);
  }
  for (const auto& [id, thread] : running_) {
    Job& job = *jobs_.at(id);
    if (!job.cancel.load() && gone(job)) {
      job.cancel_reason = "its client disconnected";
      job.cancel.store(true);
    }
  }
  while (ended_.size() > options_.job_history) {
    jobs_.erase(ended_.front());
    ended_.pop_front();
  }
}

void JobService::reply(Job& job, netmc::v1::Response response) {
  response.set_request_id(job.request_id);
  if (auto session = job.session.lock()) session->send(response);
}

void JobService::start_watch(Job& job, const std::shared_ptr<management::Peer>& session,
                             std::uint64_t request_id) {
  std::erase_if(job.watchers, [](const Watcher& watcher) {
    const auto other = watcher.session.lock();
    return !other || !other->open();
  });
  if (job.watchers.size() >= options_.max_watchers_per_job) {
    session->send(error_response(request_id, "watch: job " + std::to_string(job.id) + " has " +
                                                 std::to_string(job.watchers.size()) +
                                                 " watchers already (the server's limit)"));
    return;
  }
  netmc::v1::Response response;
  response.set_request_id(request_id);
  *response.mutable_status()->add_jobs() = job.status;
  session->send(response);
  const auto send_iteration = [&](const netmc::v1::IterationMetrics& metrics) {
    netmc::v1::Response update;
    update.set_request_id(request_id);
    update.mutable_iteration()->set_job_id(job.id);
    update.mutable_iteration()->set_total_iterations(job.status.iterations_total());
    *update.mutable_iteration()->mutable_metrics() = metrics;
    session->send(update);
  };
  const std::string& state = job.status.state();
  if (state == "queued" || state == "running") {
    for (const auto& metrics : job.iterations) send_iteration(metrics);
    job.watchers.push_back({session, request_id});
    session->hold();  // not idle while it waits for the job
    return;
  }
  // Ended. A job dropped from the queue never ran: its end is its status.
  netmc::v1::JobFinished finished;
  if (job.finished) {
    finished = *job.finished;
  } else {
    finished.set_job_id(job.id);
    finished.set_state(state);
    finished.set_error(job.status.error());
  }
  for (const auto& metrics : finished.result().iterations()) send_iteration(metrics);
  netmc::v1::Response end;
  end.set_request_id(request_id);
  *end.mutable_finished() = std::move(finished);
  session->send(end);
}

void JobService::end_watches(Job& job, const netmc::v1::JobFinished& finished) {
  for (const auto& watcher : job.watchers) {
    const auto session = watcher.session.lock();
    if (!session) continue;
    netmc::v1::Response end;
    end.set_request_id(watcher.request_id);
    *end.mutable_finished() = finished;
    session->send(end);
    session->release();
  }
  job.watchers.clear();
  job.iterations.clear();  // the end carries them
}

void JobService::schedule() {
  std::unique_lock lock(mutex_);
  while (true) {
    for (auto& thread : finished_) thread.join();
    finished_.clear();
    if (stopping_) break;
    std::vector<std::vector<std::string>> queued;
    for (const auto& job : queue_) queued.push_back(job->axes);
    const auto start = admissible_jobs(queued, busy_axes_, running_.size(), options_.max_running_jobs);
    std::vector<std::shared_ptr<Job>> starting;
    for (const std::size_t index : start) starting.push_back(queue_[index]);
    for (const auto& job : starting) {
      queue_.erase(std::find(queue_.begin(), queue_.end(), job));
      queued_spec_bytes_ -= job->spec_bytes;
      busy_axes_.insert(job->axes.begin(), job->axes.end());
      job->status.set_state("running");
      job->status.clear_waiting_for();
      spdlog::info("job {} running on axes {} ({} running, {} queued)", job->id, fmt::join(job->axes, ","),
                   running_.size() + 1,
                   queue_.size());
      running_.emplace(job->id, std::thread([this, job] {
        run(job);
        finish(job);
      }));
    }
    // What each waiting job waits behind, for `netmc status`.
    std::vector<JobAxes> running_axes, queued_before;
    for (const auto& [id, thread] : running_) running_axes.push_back({id, jobs_.at(id)->axes});
    for (const auto& job : queue_) {
      job->status.set_waiting_for(waiting_for(job->axes, running_axes, queued_before, options_.max_running_jobs));
      queued_before.push_back({job->id, job->axes});
    }
    tend_jobs();
    // Woken by submissions and ends of jobs; every quarter second anyway, to see closed clients.
    wake_.wait_for(lock, std::chrono::milliseconds(250));
  }
  // Stopping: the jobs were cancelled; wait for their threads.
  while (!running_.empty()) {
    wake_.wait(lock);
    for (auto& thread : finished_) thread.join();
    finished_.clear();
  }
}

void JobService::finish(const std::shared_ptr<Job>& job) {
  if (const auto session = job->session.lock()) session->release();
  {
    std::lock_guard lock(mutex_);
    ended_.push_back(job->id);
    job->spec = netmc::v1::JobSpec();  // an ended job keeps its status and result, not its spec
    for (const auto& axis : job->axes) busy_axes_.erase(axis);
    const auto it = running_.find(job->id);
    finished_.push_back(std::move(it->second));
    running_.erase(it);
  }
  wake_.notify_all();
}

const JobService::AxisReaders& JobService::axis_readers(bool realtime, const std::string& axis) {
  // Made on first use and kept, like the setpoint writers: an axis belongs to one job at a time,
  // and a reader made per job would have to be discovered anew by the node first (over a lossy
  // network, seconds) before its feedback reaches the job.
  std::lock_guard lock(endpoints_mutex_);
  auto& readers = axis_readers_[{realtime, axis}];
  if (!readers.feedback) {
    const std::vector<std::string> partition{dds::partition_of_axis(axis)};
    readers.feedback = context_.reader(
        context_.topic<netmc::dds::FeedbackPubSubType>(realtime ? dds::kRealtimeFeedbackTopic
                                                                : dds::kLockstepFeedbackTopic),
        realtime ? dds::Delivery::stream : dds::Delivery::exchange, partition);
    readers.events = context_.reader(context_.topic<netmc::dds::AxisEventPubSubType>(dds::kAxisEventTopic),
                                     dds::Delivery::control, partition);
  }
  return readers;
}

eprosima::fastdds::dds::DataWriter* JobService::setpoint_writer(bool realtime, const std::string& axis) {
  // One writer per axis and clock, in the axis's partition; made on first use and kept (at most
  // one per axis a node ever hosted: bounded by the lab's axes).
  std::lock_guard lock(endpoints_mutex_);
  auto& writer = setpoint_writers_[{realtime, axis}];
  if (!writer) {
    writer = context_.writer(context_.topic<netmc::dds::SetpointPubSubType>(
                                 realtime ? dds::kRealtimeSetpointTopic : dds::kLockstepSetpointTopic),
                             realtime ? dds::Delivery::stream : dds::Delivery::exchange, dds::partition_of_axis(axis));
  }
  return writer;
}

std::vector<NodeRecord> JobService::find_nodes(const Job& job, const JobChannels& channels) {
  const std::string clock = job.spec.clock().empty() ? "lockstep" : job.spec.clock();
  const bool realtime = clock == "realtime";
  std::vector<NodeRecord> found;
  std::vector<std::string> participants;
  for (const auto& axis : job::axis_names(job.spec)) {
    const auto deadline = std::chrono::steady_clock::now() + options_.discovery_timeout;
    std::optional<NodeRecord> node;
    while (!(node = nodes_.node_for_axis(axis)) && std::chrono::steady_clock::now() < deadline &&
           !job.cancel.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (!node) {
      // Say what was found: a misspelt axis or a node started without it is then plain to see.
      std::string seen;
      for (const auto& known : nodes_.nodes()) {
        std::string axes;
        for (const auto& name : known.status.axes()) axes += (axes.empty() ? "" : ",") + name;
        seen += (seen.empty() ? "" : "; ") + known.status.node() + " (" + axes + ")";
      }
      throw JobFailure("no axis node for axis " + axis + " was discovered within " +
                       std::to_string(options_.discovery_timeout.count()) + " ms (nodes discovered: " +
                       (seen.empty() ? std::string("none") : seen) +
                       "); start a node with netmc-axis --axes " + axis + ", or choose the job's axes with --axes");
    }
    if (node->status.clock() != clock) {
      throw JobFailure("node " + node->status.node() + " runs the " + node->status.clock() +
                       " clock but the job needs " + clock + ": start the node with netmc-axis --clock " + clock +
                       ", or run the job with --clock " + node->status.clock());
    }
    if (node->status.plant() != job.spec.plant()) {
      throw JobFailure("node " + node->status.node() + " hosts plant '" + node->status.plant() +
                       "' but the job needs '" + job.spec.plant() + "': start the node with netmc-axis --plant " +
                       job.spec.plant());
    }
    // Another server's hold: a server that died (or this one before its restart) holds the axis
    // until the node's hold lease ends (10 s without contact); a live one keeps it.
    const auto foreign_hold = [&]() -> const netmc::dds::AxisHold* {
      for (const auto& hold : node->status.holds()) {
        if (hold.axis() == axis && hold.server() != context_.identity()) return &hold;
      }
      return nullptr;
    };
    const auto hold_deadline = std::chrono::steady_clock::now() + options_.foreign_hold_wait;
    while (foreign_hold() && std::chrono::steady_clock::now() < hold_deadline && !job.cancel.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (auto again = nodes_.node_for_axis(axis)) node = std::move(again);
    }
    if (const auto* hold = foreign_hold()) {
      throw JobFailure("axis " + axis + " (node " + node->status.node() + ") is held by server " + hold->server() +
                       ", job " + std::to_string(hold->job_id()) + " (waited " +
                       std::to_string(options_.foreign_hold_wait.count()) + " ms)");
    }
    found.push_back(*node);
    participants.push_back(node->status.participant());
    if (!context_.wait_for_participants(setpoint_writer(realtime, axis), {participants.back()},
                                        options_.discovery_timeout)) {
      throw JobFailure("node " + node->status.node() + " was discovered but does not read the setpoints of axis " +
                       axis + " within " + std::to_string(options_.discovery_timeout.count()) + " ms");
    }
  }
  // The very participants that host the axes must be matched both ways (our control and
  // setpoints, above, to their readers, their feedback and events to ours): an endpoint of a node that
  // died, which DDS still counts for its lease, does not do.
  bool matched = context_.wait_for_participants(control_, participants, options_.discovery_timeout);
  for (std::size_t axis = 0; matched && axis < participants.size(); ++axis) {
    matched = context_.wait_for_participants(channels.feedback->readers().at(axis), {participants[axis]},
                                             options_.discovery_timeout) &&
              context_.wait_for_participants(channels.events->readers().at(axis), {participants[axis]},
                                             options_.discovery_timeout);
  }
  if (!matched) {
    throw JobFailure("the axis nodes were discovered but their readers did not match within " +
                     std::to_string(options_.discovery_timeout.count()) + " ms");
  }
  return found;
}

void JobService::run(const std::shared_ptr<Job>& shared_job) {
  Job& job = *shared_job;
  netmc::v1::JobFinished done;
  done.set_job_id(job.id);
  std::string state = "done";
  try {
    if (job.cancel.load()) throw JobFailure("cancelled before it started");
    realtime::tighten_timer_slack();  // this thread sleeps to cycle deadlines
    const bool realtime = job.spec.clock() == "realtime";
    // The readers of the job's own axes (each in its axis's partition): the job sees its axes'
    // samples and no others, and no job waits for discovery of readers made for it.
    std::vector<eprosima::fastdds::dds::DataReader*> feedback_readers, event_readers;
    for (const auto& axis : job.axes) {
      const AxisReaders& readers = axis_readers(realtime, axis);
      feedback_readers.push_back(readers.feedback);
      event_readers.push_back(readers.events);
    }
    dds::SampleReader<netmc::dds::Feedback> feedback(feedback_readers);
    dds::SampleReader<netmc::dds::AxisEvent> events(event_readers);
    JobChannels channels;
    channels.server = context_.identity();
    channels.axes = job.axes;
    channels.control = control_;
    channels.feedback = &feedback;
    channels.events = &events;
    channels.iteration_logs = iteration_logs_;
    for (const auto& axis : channels.axes) channels.setpoints.push_back(setpoint_writer(realtime, axis));
    // "running 0/N" alone would read as a loop that does not start: say what it waits for.
    set_waiting_for(job, "its axis nodes (discovery, up to " + std::to_string(options_.discovery_timeout.count()) +
                             " ms per axis)");
    const std::vector<NodeRecord> nodes = find_nodes(job, channels);
    set_waiting_for(job, "");
    for (const auto& node : nodes) channels.nodes.push_back(node.status.participant());
    struct ReportForgeries {
      const JobChannels& channels;
      std::uint64_t job_id;
      JobService& service;
      ~ReportForgeries() {
        if (channels.forged_samples == 0) return;
        {
          std::lock_guard lock(service.mutex_);
          service.totals_.forged_samples += channels.forged_samples;
        }
        spdlog::warn("job {}: dropped {} forged feedback or axis events (about its axes, from participants that do "
                     "not host them)",
                     job_id, channels.forged_samples);
      }
    } report_forgeries{channels, job.id, *this};
    std::uint64_t job_cycles = 0;  // per iteration, for the loop delay's count
    const auto on_iteration = [&](const sim::IterationRecord& record) {
      const auto metrics = job::to_proto(record.metrics);
      *done.mutable_result()->add_iterations() = metrics;
      netmc::v1::Response update;
      auto& iteration = *update.mutable_iteration();
      iteration.set_job_id(job.id);
      iteration.set_total_iterations(job.spec.iterations());
      *iteration.mutable_metrics() = metrics;
      // Watchers and the client hear of the iteration once it is kept (written, with a store).
      auto deliver = [this, shared_job, update]() mutable {
        {
          std::lock_guard lock(mutex_);
          shared_job->iterations.push_back(update.iteration().metrics());
          for (const auto& watcher : shared_job->watchers) {
            if (const auto session = watcher.session.lock()) {
              update.set_request_id(watcher.request_id);
              session->send(update);
            }
          }
        }
        reply(*shared_job, update);
      };
      if (options_.store) {
        options_.store->iteration(job.id, static_cast<std::uint32_t>(record.metrics.iteration),
                                  metrics.SerializeAsString(), std::move(deliver));
      } else {
        deliver();
      }
      {
        std::lock_guard lock(mutex_);
        const auto& m = record.metrics;
        ++totals_.iterations;
        totals_.deadline_misses += m.deadline_misses;
        totals_.lost_feedback += m.lost_feedback;
        totals_.lost_setpoints += m.lost_setpoints;
        totals_.tau_p50_s = m.tau_p50_s;
        totals_.tau_p99_s = m.tau_p99_s;
        totals_.tau_max_s = m.tau_max_s;
        const std::uint64_t delays = job_cycles > m.lost_setpoints ? job_cycles - m.lost_setpoints : 0;
        totals_.tau_sum_s += m.tau_mean_s * static_cast<double>(delays);
        totals_.tau_count += delays;
        job.status.set_iterations_done(static_cast<std::uint32_t>(record.metrics.iteration));
      }
      spdlog::info("job {} iteration {}/{}: e_max {:.4f} mm, e_sum {:.3f} mm{}", job.id, record.metrics.iteration,
                   job.spec.iterations(), record.metrics.e_max_m * 1e3, record.metrics.e_sum_m * 1e3,
                   record.metrics.deadline_misses > 0
                       ? fmt::format(", {} deadline misses", record.metrics.deadline_misses)
                       : std::string());
    };
    // Either clock's runner: its description kept, its cycles counted, the console's live view.
    const auto run_with = [&](auto& runner) {
      *done.mutable_result() = job::describe_run(job.spec, runner.controller_description());
      if (options_.store) options_.store->started(job.id, done.result().SerializeAsString());
      job_cycles = runner.cycles();
      if (auto live = options_.live_cycles ? options_.live_cycles(job.id) : nullptr) runner.set_cycle_listener(live);
      runner.run(on_iteration, job.cancel);
    };
    if (realtime) {
      // Before the first iteration every node's clock must have been measured a few times.
      const auto deadline = std::chrono::steady_clock::now() + options_.discovery_timeout;
      for (const auto& node : nodes) {
        while (!clocks_.estimate(node.status.node(), 4) && std::chrono::steady_clock::now() < deadline) {
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
      }
      const ClockOffsets offsets = [this, &nodes, &channels](std::size_t axis) {
        const auto estimate = clocks_.estimate(nodes.at(axis).status.node());
        if (!estimate) {
          throw JobFailure("axis " + channels.axes.at(axis) + " (node " + nodes.at(axis).status.node() +
                           ") answers no clock probe: node stopped or unreachable");
        }
        return *estimate;
      };
      RealtimeDdsRunner runner(channels, job.spec, job.id, {options_.axis_timeout, options_.silence_limit, options_.positioning_timeout},
                               clocks_.time_base(), offsets, options_.build_options());
      run_with(runner);
    } else {
      LockstepDdsRunner runner(channels, job.spec, job.id, options_.axis_timeout, options_.build_options());
      run_with(runner);
    }
    if (job.cancel.load()) state = "cancelled";
  } catch (const std::exception& error) {
    state = job.cancel.load() ? "cancelled" : "failed";
    done.set_error(error.what());
  }
  {
    std::lock_guard lock(mutex_);
    // A cancelled job ends for its reason; what it was doing when it stopped matters less.
    if (state == "cancelled") done.set_error(job.cancel_reason);
  }
  done.set_state(state);
  const auto level = state == "failed" ? spdlog::level::err : spdlog::level::info;
  spdlog::log(level, "job {} {}{}", job.id, state, done.error().empty() ? "" : ": " + done.error());
  conclude(shared_job, std::move(done));
}

void JobService::conclude(const std::shared_ptr<Job>& job, netmc::v1::JobFinished finished) {
  auto tell = [this, job, finished]() {
    {
      std::lock_guard lock(mutex_);
      job->status.set_state(finished.state());
      job->status.set_error(finished.error());
      job->ended_unix_s = unix_now_s();
      job->finished = finished;
      end_watches(*job, finished);
    }
    netmc::v1::Response end;
    *end.mutable_finished() = finished;
    reply(*job, end);
  };
  if (options_.store) {
    options_.store->ended(job->id, finished.state(), finished.error(), finished.SerializeAsString(), std::move(tell));
  } else {
    tell();
  }
}

void JobService::set_waiting_for(Job& job, const std::string& what) {
  std::lock_guard lock(mutex_);
  if (what.empty()) {
    job.status.clear_waiting_for();
  } else {
    job.status.set_waiting_for(what);
  }
}

void JobService::end_queued(Job& job, const std::string& reason) {
  queued_spec_bytes_ -= job.spec_bytes;
  job.spec = netmc::v1::JobSpec();
  job.status.set_state("cancelled");
  job.status.set_error(reason);
  job.status.clear_waiting_for();
  job.ended_unix_s = unix_now_s();
  netmc::v1::JobFinished finished;
  finished.set_job_id(job.id);
  finished.set_state("cancelled");
  finished.set_error(reason);
  job.finished = finished;
  end_watches(job, finished);
  ended_.push_back(job.id);
  if (const auto submitter = job.session.lock()) {
    netmc::v1::Response end;
    end.set_request_id(job.request_id);
    *end.mutable_finished() = finished;
    submitter->send(end);
    submitter->release();
  }
  if (options_.store) options_.store->ended(job.id, "cancelled", reason, finished.SerializeAsString());
}

void JobService::restore_from_store() {
  const auto contents = options_.store->load(options_.job_history);
  const auto make_job = [this](const store::StoredJob& stored) {
    auto job = std::make_shared<Job>();
    job->id = stored.id;
    job->owner = stored.owner;
    job->accepted_unix_s = stored.accepted_unix_s;
    job->ended_unix_s = stored.ended_unix_s;
    // No connection outlived the restart: the job is the server's until it ends.
    job->keep_after_disconnect = true;
    job->status.set_job_id(stored.id);
    job->status.set_state(stored.state);
    job->status.set_error(stored.error);
    job->status.set_label(stored.label);
    job->status.set_iterations_total(stored.iterations_total);
    job->status.set_iterations_done(stored.iterations_done);
    jobs_[job->id] = job;
    return job;
  };
  for (const auto& stored : contents.ended) {
    auto job = make_job(stored);
    netmc::v1::JobFinished finished;
    if (finished.ParseFromString(stored.finished)) job->finished = std::move(finished);
    ended_.push_back(job->id);
  }
  std::size_t requeued = 0, failed = 0;
  for (const auto& stored : contents.unfinished) {
    auto job = make_job(stored);
    if (stored.state == "running") {
      // What it finished is kept; the iteration under way when the server stopped is lost.
      netmc::v1::JobFinished finished;
      finished.set_job_id(job->id);
      finished.set_state("failed");
      finished.set_error("server restarted during iteration " + std::to_string(stored.iterations.size() + 1));
      (void)finished.mutable_result()->ParseFromString(stored.result_header);
      for (const auto& iteration : stored.iterations) {
        (void)finished.mutable_result()->add_iterations()->ParseFromString(iteration.metrics);
      }
      job->status.set_state("failed");
      job->status.set_error(finished.error());
      job->ended_unix_s = unix_now_s();
      job->finished = finished;
      ended_.push_back(job->id);
      options_.store->ended(job->id, "failed", finished.error(), finished.SerializeAsString());
      ++failed;
      continue;
    }
    if (!job->spec.ParseFromString(stored.spec)) {
      job->status.set_state("failed");
      job->status.set_error("its stored spec cannot be read");
      options_.store->ended(job->id, "failed", job->status.error(), {});
      ended_.push_back(job->id);
      continue;
    }
    job->spec_bytes = job->spec.ByteSizeLong();
    job->axes = job::axis_names(job->spec);
    queued_spec_bytes_ += job->spec_bytes;
    queue_.push_back(job);
    ++requeued;
  }
  spdlog::info("job store {}: {} ended jobs in memory, {} queued again, {} failed by the restart",
               options_.store->file().string(), contents.ended.size(), requeued, failed);
}

netmc::v1::JobList JobService::list_jobs(const netmc::v1::ListJobs& request) const {
  store::JobFilter filter;
  filter.state = request.state();
  filter.label_contains = request.label_contains();
  filter.since_unix_s = request.since_unix_s();
  filter.limit = request.limit() == 0 ? 50 : std::min<std::uint32_t>(request.limit(), 10000);
  static const std::set<std::string> states{"", "queued", "running", "done", "failed", "cancelled"};
  if (!states.contains(filter.state)) {
    throw std::invalid_argument("state: '" + filter.state.substr(0, 32) +
                                "' is none of queued, running, done, failed, cancelled");
  }
  if (!std::isfinite(filter.since_unix_s)) throw std::invalid_argument("since: not a finite time");
  if (filter.label_contains.size() > 256) throw std::invalid_argument("label: longer than 256 characters");
  netmc::v1::JobList list;
  const auto add = [&list](std::uint64_t id, const std::string& label, const std::string& state,
                           const std::string& error, const std::string& owner, double accepted, double ended,
                           std::uint32_t done, std::uint32_t total) {
    auto& record = *list.add_jobs();
    record.set_job_id(id);
    record.set_label(label);
    record.set_state(state);
    record.set_error(error);
    record.set_owner(owner);
    record.set_accepted_unix_s(accepted);
    record.set_ended_unix_s(ended);
    record.set_iterations_done(done);
    record.set_iterations_total(total);
  };
  if (options_.store) {
    // The store's state lags the memory's by the writes queued: a running job is "running" in
    // both; its end shows once written.
    list.set_persistent(true);
    for (const auto& job : options_.store->list(filter)) {
      add(job.id, job.label, job.state, job.error, job.owner, job.accepted_unix_s, job.ended_unix_s,
          job.iterations_done, job.iterations_total);
    }
    return list;
  }
  std::lock_guard lock(mutex_);
  for (auto it = jobs_.rbegin(); it != jobs_.rend() && list.jobs_size() < static_cast<int>(filter.limit); ++it) {
    const Job& job = *it->second;
    const auto& status = job.status;
    if (!filter.state.empty() && status.state() != filter.state) continue;
    if (!filter.label_contains.empty() && status.label().find(filter.label_contains) == std::string::npos) continue;
    if (job.accepted_unix_s < filter.since_unix_s) continue;
    add(job.id, status.label(), status.state(), status.error(), job.owner, job.accepted_unix_s, job.ended_unix_s,
        status.iterations_done(), status.iterations_total());
  }
  return list;
}

}  // namespace netmc::service
