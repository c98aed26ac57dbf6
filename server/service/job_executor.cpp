#include "server/service/job_executor.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <optional>
#include <thread>

#include "dds_typesPubSubTypes.h"
#include "server/dds/topics.hpp"
#include "server/job/job_builder.hpp"
#include "server/realtime/realtime_scheduling.hpp"
#include "server/service/lockstep_dds_runner.hpp"
#include "server/service/realtime_dds_runner.hpp"

namespace netmc::service {

JobExecutor::JobExecutor(dds::DdsContext& context, NodeDirectory& nodes, ClockTracker& clocks, JobRegistry& registry,
                         const JobServiceOptions& options)
    : context_(context),
      nodes_(nodes),
      clocks_(clocks),
      registry_(registry),
      options_(options),
      control_(context.writer(context.topic<netmc::dds::JobControlPubSubType>(dds::kJobControlTopic),
                              dds::Delivery::control)),
      iteration_logs_(context.writer(
          context.topic<netmc::dds::IterationLogPubSubType>(dds::kIterationLogTopic),
          dds::Delivery::log)) {}

const JobExecutor::AxisReaders& JobExecutor::axis_readers(bool realtime, const std::string& axis) {
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

eprosima::fastdds::dds::DataWriter* JobExecutor::setpoint_writer(bool realtime, const std::string& axis) {
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

std::vector<NodeRecord> JobExecutor::find_nodes(const Job& job, const JobChannels& channels) {
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
    // A drive in fault, or that does not answer, cannot start: said now, naming the node's reason.
    for (const auto& drive : node->status.drives()) {
      if (drive.axis() != axis) continue;
      if (drive.fault_latched() || drive.state() == "Fault" || drive.state() == "no answer") {
        throw JobFailure("axis " + axis + " is in fault: node " + node->status.node() + " reports " +
                         node->status.detail() + "; netmc reset " + node->status.node() + " once the cause is gone");
      }
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

void JobExecutor::run(const std::shared_ptr<Job>& shared_job) {
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
    registry_.set_waiting_for(job, "its axis nodes (discovery, up to " + std::to_string(options_.discovery_timeout.count()) +
                             " ms per axis)");
    const std::vector<NodeRecord> nodes = find_nodes(job, channels);
    registry_.set_waiting_for(job, "");
    for (const auto& node : nodes) channels.nodes.push_back(node.status.participant());
    struct ReportForgeries {
      const JobChannels& channels;
      std::uint64_t job_id;
      JobRegistry& registry;
      ~ReportForgeries() {
        if (channels.forged_samples == 0) return;
        registry.count_forged_samples(channels.forged_samples);
        spdlog::warn("job {}: dropped {} forged feedback or axis events (about its axes, from participants that do "
                     "not host them)",
                     job_id, channels.forged_samples);
      }
    } report_forgeries{channels, job.id, registry_};
    std::uint64_t job_cycles = 0;  // per iteration, for the loop delay's count
    const auto on_iteration = [&](const sim::IterationRecord& record) {
      const auto metrics = job::to_proto(record.metrics);
      *done.mutable_result()->add_iterations() = metrics;
      netmc::v1::Response update;
      auto& iteration = *update.mutable_iteration();
      iteration.set_job_id(job.id);
      iteration.set_total_iterations(job.spec.iterations());
      *iteration.mutable_metrics() = metrics;
      registry_.report_iteration(shared_job, std::move(update));
      registry_.count_iteration(job, record.metrics, job_cycles);
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
    // Failed while its axes ran (the runner had started): the iteration under way never ended.
    if (state == "failed" && done.has_result() && done.result().iterations_size() < static_cast<int>(job.spec.iterations()) &&
        !done.result().controller().empty()) {
      registry_.count_failed_iteration();
    }
  }
  // A cancelled job ends for its reason; what it was doing when it stopped matters less.
  if (state == "cancelled") done.set_error(registry_.cancel_reason(job));
  done.set_state(state);
  const auto level = state == "failed" ? spdlog::level::err : spdlog::level::info;
  spdlog::log(level, "job {} {}{}", job.id, state, done.error().empty() ? "" : ": " + done.error());
  registry_.conclude(shared_job, done);
}

}  // namespace netmc::service
