// Test tool: a rogue participant on a netmc DDS domain, for integration.rogue_participant. It
// links the generated types and speaks the data plane as netmc-server and netmc-axis do, but as
// nobody it should be believed as:
//   drive   acts as a server of its own on an idle axis: BEGIN_ITERATION with its own job spec,
//           then commands of --command (1e30, or NaN with --nan); prints what the axis reported.
//   hijack  waits for a real server's job on --axis and, while it runs, speaks in that server's
//           and that axis node's name: setpoints with sequence number 2^64-2 and NaN commands
//           for the next cycle, fake feedback, a fake fault, a fake END_JOB, and node statuses
//           that spoof the node (its participant, its name, its axes). Prints what it sent.
//   begin   acts as a server that never reads: BEGIN_ITERATION of its own job to an idle --axis
//           every --every seconds, with no feedback or event reader, so the node can never
//           start the job (its server must read the axis's feedback first). --count stops
//           after that many; --spec-bytes pads each job spec to that size (an unknown field:
//           the spec still parses), to see what held starts cost a node.
//   flood   --count random setpoints as fast as it can to the partitions of --axis (comma-
//           separated axes), on the setpoint topic of the node's clock: random server (its own
//           identity, a made-up one), job, iteration, cycle and command. Prints the rate.
//           --control: random END_ITERATION and END_JOB job controls instead.
// Without DDS Security every participant on the domain can do this; what netmc promises is
// that none of it moves an axis of the real server's job or changes its result.

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <csignal>
#include <limits>
#include <optional>
#include <random>
#include <thread>
#include <vector>

#include "dds_typesPubSubTypes.h"
#include "idl/job.pb.h"
#include "server/dds/dds_context.hpp"
#include "server/dds/time_base.hpp"
#include "server/dds/topics.hpp"
#include "server/job/job_builder.hpp"

namespace {

namespace nd = netmc::dds;
using Clock = std::chrono::steady_clock;

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop.store(true); }

struct Options {
  nd::DdsOptions dds;
  std::string axis;
  std::string clock = "lockstep";
  double command = 1e30;
  bool nan = false;
  double seconds = 30.0;
  double every_s = 1.0;
  std::size_t count = 300000;
  std::size_t begins = std::numeric_limits<std::size_t>::max();
  std::size_t spec_bytes = 0;
  bool control = false;
  bool reading_feedback = false;
};

// The status of the node hosting `axis` (its participant, plant, clock), once it is discovered.
std::optional<nd::NodeStatus> find_node(nd::SampleReader<nd::NodeStatus>& statuses, const std::string& axis,
                                        Clock::time_point until) {
  while (auto status = statuses.take_until(until)) {
    for (const auto& a : status->axes()) {
      if (a == axis && status->health() != nd::NODE_REFUSED && status->health() != nd::NODE_LEAVING) return status;
    }
  }
  return std::nullopt;
}

// The job spec the rogue's own jobs carry: a small circle on the axis and one it makes up.
std::vector<std::uint8_t> rogue_job_spec(const nd::NodeStatus& node, const std::string& axis, const std::string& clock) {
  netmc::v1::JobSpec spec;
  spec.set_plant(node.plant());
  spec.set_clock(clock);
  spec.add_axes(axis);
  spec.add_axes(axis + "-other");
  auto& circle = *spec.mutable_trajectory()->mutable_circle();
  circle.set_radius_m(0.01);
  circle.set_period_s(8.0);
  netmc::job::apply_defaults(spec);
  const std::string bytes = spec.SerializeAsString();
  return {bytes.begin(), bytes.end()};
}

// `spec` padded to `size` bytes with field 1000 (length-delimited, zeros): a field no JobSpec
// has, which protobuf keeps as unknown, so the spec still parses.
void pad_spec(std::vector<std::uint8_t>& spec, std::size_t size) {
  const auto varint = [&spec](std::uint64_t value) {
    do {
      const auto low = static_cast<std::uint8_t>(value & 0x7F);
      value >>= 7;
      spec.push_back(value ? static_cast<std::uint8_t>(low | 0x80) : low);
    } while (value);
  };
  constexpr std::size_t kHeader = 2 + 4;  // the tag of field 1000 and a length of up to 4 bytes
  if (size <= spec.size() + kHeader) return;
  const std::size_t padding = size - spec.size() - kHeader;
  varint((1000u << 3) | 2u);
  varint(padding);
  spec.resize(spec.size() + padding, 0);
}

int drive(const Options& options) {
  nd::DdsContext context(options.dds);
  const bool realtime = options.clock == "realtime";
  const std::string partition = nd::partition_of_axis(options.axis);
  nd::SampleReader<nd::NodeStatus> statuses(
      context.reader(context.topic<nd::NodeStatusPubSubType>(nd::kNodeStatusTopic), nd::Delivery::status));
  nd::SampleReader<nd::Feedback> feedback(context.reader(
      context.topic<nd::FeedbackPubSubType>(realtime ? nd::kRealtimeFeedbackTopic : nd::kLockstepFeedbackTopic),
      realtime ? nd::Delivery::stream : nd::Delivery::exchange, {partition}));
  nd::SampleReader<nd::AxisEvent> events(context.reader(
      context.topic<nd::AxisEventPubSubType>(nd::kAxisEventTopic), nd::Delivery::control, {partition}));
  auto* control = context.writer(context.topic<nd::JobControlPubSubType>(nd::kJobControlTopic), nd::Delivery::control);
  auto* setpoints = context.writer(
      context.topic<nd::SetpointPubSubType>(realtime ? nd::kRealtimeSetpointTopic : nd::kLockstepSetpointTopic),
      realtime ? nd::Delivery::stream : nd::Delivery::exchange, partition);

  const auto node = find_node(statuses, options.axis, Clock::now() + std::chrono::seconds(10));
  if (!node) {
    fmt::print("rogue: no node hosts axis {}\n", options.axis);
    return 1;
  }
  if (!context.wait_for_participants(control, {node->participant()}, std::chrono::seconds(10)) ||
      !context.wait_for_participants(setpoints, {node->participant()}, std::chrono::seconds(10))) {
    fmt::print("rogue: node {} does not read our job control and setpoints\n", node->node());
    return 1;
  }
  const std::uint64_t job_id = 4242;
  const double start_s = realtime ? nd::time_base_now_s(nd::parse_time_base(node->time_base())) + 0.3 : 0.0;
  nd::JobControl begin;
  begin.axis(options.axis);
  begin.server(context.identity());
  begin.job_id(job_id);
  begin.iteration(1);
  begin.kind(nd::CONTROL_BEGIN_ITERATION);
  begin.start_position_m(0.0);
  begin.start_time_s(start_s);
  begin.job_spec(rogue_job_spec(*node, options.axis, options.clock));
  nd::write_checked(control, &begin);
  fmt::print("rogue: sent BEGIN_ITERATION of its own job {} to axis {} (node {})\n", job_id, options.axis,
             node->node());

  const double command = options.nan ? std::numeric_limits<double>::quiet_NaN() : options.command;
  double max_position = 0.0;
  std::size_t samples = 0, sent = 0;
  std::string event_text = "none";
  const auto take_reports = [&](Clock::time_point until) {
    while (auto sample = feedback.take_until(std::min(until, Clock::now() + std::chrono::milliseconds(1)))) {
      if (sample->job_id() != job_id || sample->kind() != nd::FEEDBACK_SAMPLE) continue;
      ++samples;
      max_position = std::max(max_position, std::abs(sample->true_position_m()));
    }
    while (auto event = events.try_take()) {
      if (event->job_id() == job_id && event->kind() != nd::AXIS_ITERATION_ENDED) {
        event_text = fmt::format("{}: {}", event->kind() == nd::AXIS_FAULT ? "AXIS_FAULT" : "AXIS_REFUSED",
                                 event->detail());
      }
    }
  };
  // As a lockstep server does, the first command goes once the axis has answered the BEGIN (its
  // sample of cycle 0): a command that overtakes the BEGIN finds the axis held by no one, and the
  // node drops it on arrival.
  const auto answered = Clock::now() + std::chrono::seconds(2);
  while (!realtime && samples == 0 && event_text == "none" && Clock::now() < answered && !g_stop.load()) {
    take_reports(Clock::now() + std::chrono::milliseconds(20));
  }
  const auto end = Clock::now() + std::chrono::milliseconds(static_cast<long>(options.seconds * 1e3));
  for (std::uint64_t cycle = 0; Clock::now() < end && !g_stop.load() && event_text == "none"; ++cycle) {
    nd::Setpoint setpoint;
    setpoint.axis(options.axis);
    setpoint.server(context.identity());
    setpoint.job_id(job_id);
    setpoint.iteration(1);
    setpoint.cycle(cycle);
    setpoint.command(command);
    setpoint.send_time_s(realtime ? nd::time_base_now_s(nd::parse_time_base(node->time_base())) - start_s : 0.0);
    nd::write_checked(setpoints, &setpoint);
    ++sent;
    take_reports(Clock::now() + std::chrono::milliseconds(realtime ? 1 : 20));
  }
  take_reports(Clock::now() + std::chrono::milliseconds(500));
  for (const auto kind : {nd::CONTROL_END_ITERATION, nd::CONTROL_END_JOB}) {
    begin.kind(kind);
    begin.job_spec({});
    nd::write_checked(control, &begin);
  }
  fmt::print("rogue: axis {}: {} commands of {} sent, {} samples back, largest |position| {:.3g} m, event {}\n",
             options.axis, sent, command, samples, max_position, event_text);
  return 0;
}

int begin_without_reader(const Options& options) {
  nd::DdsContext context(options.dds);
  nd::SampleReader<nd::NodeStatus> statuses(
      context.reader(context.topic<nd::NodeStatusPubSubType>(nd::kNodeStatusTopic), nd::Delivery::status));
  auto* control = context.writer(context.topic<nd::JobControlPubSubType>(nd::kJobControlTopic), nd::Delivery::control);
  const auto node = find_node(statuses, options.axis, Clock::now() + std::chrono::seconds(10));
  if (!node) {
    fmt::print("rogue: no node hosts axis {}\n", options.axis);
    return 1;
  }
  // --reading-feedback: the axis's feedback and events read, but no setpoint writer: a server
  // whose setpoints the node would never hear.
  // (The context keeps the readers; nothing is taken from them.)
  if (options.reading_feedback) {
    const bool realtime = node->clock() == "realtime";
    const std::string partition = nd::partition_of_axis(options.axis);
    context.reader(
        context.topic<nd::FeedbackPubSubType>(realtime ? nd::kRealtimeFeedbackTopic : nd::kLockstepFeedbackTopic),
        realtime ? nd::Delivery::stream : nd::Delivery::exchange, {partition});
    context.reader(context.topic<nd::AxisEventPubSubType>(nd::kAxisEventTopic), nd::Delivery::control, {partition});
  }
  if (!context.wait_for_participants(control, {node->participant()}, std::chrono::seconds(10))) {
    fmt::print("rogue: node {} does not read our job control\n", node->node());
    return 1;
  }
  nd::JobControl begin;
  begin.axis(options.axis);
  begin.server(context.identity());
  begin.iteration(1);
  begin.kind(nd::CONTROL_BEGIN_ITERATION);
  begin.start_position_m(0.0);
  auto spec = rogue_job_spec(*node, options.axis, node->clock());
  pad_spec(spec, options.spec_bytes);
  begin.job_spec(spec);
  fmt::print("rogue: sending BEGIN_ITERATION to axis {} (node {}) every {} s, {}, job spec {} bytes\n", options.axis,
             node->node(), options.every_s,
             options.reading_feedback ? "reading its feedback, writing no setpoints" : "reading nothing", spec.size());
  std::fflush(stdout);
  std::size_t sent = 0;
  const auto end = Clock::now() + std::chrono::milliseconds(static_cast<long>(options.seconds * 1e3));
  while (Clock::now() < end && !g_stop.load() && sent < options.begins) {
    begin.job_id(5000 + sent);
    begin.start_time_s(nd::time_base_now_s(nd::parse_time_base(node->time_base())) + 0.3);
    nd::write_checked(control, &begin);
    ++sent;
    const auto next = Clock::now() + std::chrono::milliseconds(static_cast<long>(options.every_s * 1e3));
    while (Clock::now() < next && !g_stop.load()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  fmt::print("rogue: {} BEGIN_ITERATION sent to axis {}\n", sent, options.axis);
  return 0;
}

int flood(const Options& options) {
  nd::DdsContext context(options.dds);
  std::vector<std::string> axes;
  for (std::size_t from = 0; from <= options.axis.size();) {
    const auto comma = std::min(options.axis.find(',', from), options.axis.size());
    axes.push_back(options.axis.substr(from, comma - from));
    from = comma + 1;
  }
  nd::SampleReader<nd::NodeStatus> statuses(
      context.reader(context.topic<nd::NodeStatusPubSubType>(nd::kNodeStatusTopic), nd::Delivery::status));
  const auto node = find_node(statuses, axes.front(), Clock::now() + std::chrono::seconds(10));
  if (!node) {
    fmt::print("rogue: no node hosts axis {}\n", axes.front());
    return 1;
  }
  // One writer per axis partition, on the topic of the node's clock: what a server's job uses.
  const bool realtime = node->clock() == "realtime";
  std::vector<std::pair<std::string, eprosima::fastdds::dds::DataWriter*>> writers;
  for (const auto& axis : axes) {
    writers.emplace_back(axis, options.control
                                   ? context.writer(context.topic<nd::JobControlPubSubType>(nd::kJobControlTopic),
                                                    nd::Delivery::control)
                                   : context.writer(context.topic<nd::SetpointPubSubType>(
                                                        realtime ? nd::kRealtimeSetpointTopic
                                                                 : nd::kLockstepSetpointTopic),
                                                    realtime ? nd::Delivery::stream : nd::Delivery::exchange,
                                                    nd::partition_of_axis(axis)));
  }
  for (const auto& [axis, writer] : writers) {
    if (!context.wait_for_participants(writer, {node->participant()}, std::chrono::seconds(10))) {
      fmt::print("rogue: node {} does not read our setpoints for axis {}\n", node->node(), axis);
      return 1;
    }
  }
  fmt::print("rogue: flooding axes {} (node {}) with {} random {}\n", options.axis, node->node(), options.count,
             options.control ? "job controls" : "setpoints");
  std::fflush(stdout);
  std::mt19937_64 random(42);
  std::uniform_real_distribution<double> command(-1e3, 1e3);
  std::uniform_int_distribution<std::uint64_t> small(0, 7), cycle(0, 5000), any;
  const auto started = Clock::now();
  std::size_t sent = 0;
  for (; sent < options.count && !g_stop.load(); ++sent) {
    const auto& [axis, writer] = writers[sent % writers.size()];
    if (options.control) {
      nd::JobControl c;
      c.axis(axis);
      c.server(sent % 2 == 0 ? context.identity() : fmt::format("{:024x}", any(random) >> 32));
      c.job_id(small(random));
      c.iteration(static_cast<std::uint32_t>(small(random)));
      c.kind(sent % 4 < 2 ? nd::CONTROL_END_ITERATION : nd::CONTROL_END_JOB);
      c.cycle(cycle(random));
      nd::write_checked(writer, &c);
      continue;
    }
    nd::Setpoint s;
    s.axis(axis);
    s.server(sent % 2 == 0 ? context.identity() : fmt::format("{:024x}", any(random) >> 32));
    s.job_id(small(random));
    s.iteration(static_cast<std::uint32_t>(small(random)));
    s.cycle(cycle(random));
    s.command(command(random));
    s.send_time_s(0.0);
    nd::write_checked(writer, &s);
  }
  const double took_s = std::chrono::duration<double>(Clock::now() - started).count();
  fmt::print("rogue: {} random {} sent in {:.2f} s ({:.0f} per second)\n", sent,
             options.control ? "job controls" : "setpoints", took_s,
             static_cast<double>(sent) / took_s);
  return 0;
}

int hijack(const Options& options) {
  nd::DdsContext context(options.dds);
  const std::string partition = nd::partition_of_axis(options.axis);
  nd::SampleReader<nd::NodeStatus> statuses(
      context.reader(context.topic<nd::NodeStatusPubSubType>(nd::kNodeStatusTopic), nd::Delivery::status));
  auto* control_reader =
      context.reader(context.topic<nd::JobControlPubSubType>(nd::kJobControlTopic), nd::Delivery::control);
  nd::SampleReader<nd::JobControl> controls(control_reader);
  auto* control = context.writer(context.topic<nd::JobControlPubSubType>(nd::kJobControlTopic), nd::Delivery::control);
  auto* status_writer =
      context.writer(context.topic<nd::NodeStatusPubSubType>(nd::kNodeStatusTopic), nd::Delivery::status);
  auto* events = context.writer(context.topic<nd::AxisEventPubSubType>(nd::kAxisEventTopic), nd::Delivery::control,
                                partition);
  // Both clocks' topics: the rogue does not care which the job uses. It reads the real
  // setpoints to know the cycle under way.
  struct Plane {
    Plane(eprosima::fastdds::dds::DataReader* reader, eprosima::fastdds::dds::DataWriter* setpoint_writer,
          eprosima::fastdds::dds::DataWriter* feedback_writer)
        : real(reader), setpoints(setpoint_writer), feedback(feedback_writer) {}
    nd::SampleReader<nd::Setpoint> real;
    eprosima::fastdds::dds::DataWriter* setpoints;
    eprosima::fastdds::dds::DataWriter* feedback;
  };
  std::vector<std::unique_ptr<Plane>> planes;
  for (const bool realtime : {false, true}) {
    const auto delivery = realtime ? nd::Delivery::stream : nd::Delivery::exchange;
    auto* setpoint_topic =
        context.topic<nd::SetpointPubSubType>(realtime ? nd::kRealtimeSetpointTopic : nd::kLockstepSetpointTopic);
    planes.push_back(std::make_unique<Plane>(
        context.reader(setpoint_topic, delivery, {partition}), context.writer(setpoint_topic, delivery, partition),
        context.writer(context.topic<nd::FeedbackPubSubType>(realtime ? nd::kRealtimeFeedbackTopic
                                                                      : nd::kLockstepFeedbackTopic),
                       delivery, partition)));
  }
  const auto node = find_node(statuses, options.axis, Clock::now() + std::chrono::seconds(10));
  if (!node) {
    fmt::print("rogue: no node hosts axis {}\n", options.axis);
    return 1;
  }
  // Job controls are volatile: a BEGIN_ITERATION sent before this reader matched the server's
  // writer never arrives, and a short lockstep job can end before its new setpoint writer is
  // discovered. So the rogue waits until it hears a writer of job controls besides its own
  // (only a server writes them); on a loaded machine discovery can take seconds.
  if (!nd::wait_for_writers(control_reader, 2, std::chrono::seconds(10))) {
    fmt::print("rogue: no server's job-control writer was discovered within 10 s\n");
    return 1;
  }
  fmt::print("rogue: waiting for a job on axis {} (node {}, participant {})\n", options.axis, node->node(),
             node->participant());
  std::fflush(stdout);

  std::optional<nd::JobControl> job;  // the newest BEGIN_ITERATION of a real server on the axis
  std::uint64_t cycle = 0;
  std::size_t setpoints = 0, feedback = 0, faults = 0, ends = 0, spoofs = 0;
  auto next_slow = Clock::now();
  const auto end = Clock::now() + std::chrono::milliseconds(static_cast<long>(options.seconds * 1e3));
  while (Clock::now() < end && !g_stop.load()) {
    while (auto c = controls.try_take()) {
      if (c->axis() != options.axis || nd::sent_by(controls.last_sender(), context.identity())) continue;
      if (c->kind() == nd::CONTROL_BEGIN_ITERATION) {
        if (!job) fmt::print("rogue: job {} of server {} found; attacking\n", c->job_id(), c->server());
        std::fflush(stdout);
        job = *c;
        cycle = 0;
      }
    }
    for (auto& plane : planes) {
      while (auto real = plane->real.try_take()) {
        if (nd::sent_by(plane->real.last_sender(), context.identity())) continue;
        cycle = std::max(cycle, real->cycle());
        // The job's control is volatile: a rogue whose reader matched the server's writer after
        // BEGIN_ITERATION left learns the job from its setpoints instead (same server, job and
        // iteration), so the attack does not depend on discovery's timing.
        if (!job && real->axis() == options.axis) {
          nd::JobControl seen;
          seen.kind(nd::CONTROL_BEGIN_ITERATION);
          seen.axis(real->axis());
          seen.server(real->server());
          seen.job_id(real->job_id());
          seen.iteration(real->iteration());
          fmt::print("rogue: job {} of server {} found from its setpoints; attacking\n", seen.job_id(), seen.server());
          std::fflush(stdout);
          job = seen;
        }
      }
    }
    if (job) {
      for (auto& plane : planes) {
        // The sequence number that once made every later command of the server stale, and a
        // NaN command for the next cycle, both in the server's name.
        for (const std::uint64_t k : {std::numeric_limits<std::uint64_t>::max() - 1, cycle + 1}) {
          nd::Setpoint s;
          s.axis(options.axis);
          s.server(job->server());
          s.job_id(job->job_id());
          s.iteration(job->iteration());
          s.cycle(k);
          s.command(std::numeric_limits<double>::quiet_NaN());
          s.send_time_s(0.0);
          nd::write_checked(plane->setpoints, &s);
          ++setpoints;
        }
        // Feedback in the node's name, 5 mm off, for the cycles the server is about to read.
        for (std::uint64_t k = cycle; k < cycle + 3; ++k) {
          nd::Feedback f;
          f.axis(options.axis);
          f.server(job->server());
          f.job_id(job->job_id());
          f.iteration(job->iteration());
          f.cycle(k);
          f.kind(nd::FEEDBACK_SAMPLE);
          f.position_m(0.005);
          f.true_position_m(0.005);
          nd::write_checked(plane->feedback, &f);
          ++feedback;
        }
      }
    }
    if (job && Clock::now() >= next_slow) {
      next_slow = Clock::now() + std::chrono::milliseconds(100);
      nd::AxisEvent fault;
      fault.axis(options.axis);
      fault.server(job->server());
      fault.job_id(job->job_id());
      fault.iteration(job->iteration());
      fault.kind(nd::AXIS_FAULT);
      fault.detail("forged fault");
      nd::write_checked(events, &fault);
      ++faults;
      nd::JobControl release = *job;
      release.kind(nd::CONTROL_END_JOB);
      release.job_spec({});
      nd::write_checked(control, &release);
      ++ends;
      // The node's own status, re-signed with its participant: leaving, and held by another
      // server; then the node's name from the rogue's participant; then a node of the rogue's
      // claiming the real node's axes.
      // Alternately, as a node status is kept per node name: the last one of a name wins.
      nd::NodeStatus spoof = *node;
      spoof.health(nd::NODE_LEAVING);
      nd::AxisHold hold;
      hold.axis(options.axis);
      hold.server(std::string(24, 'f'));
      hold.job_id(1);
      spoof.holds({hold});
      if (faults % 2 == 0) {
        spoof = *node;
        spoof.participant(context.identity());
      }
      nd::write_checked(status_writer, &spoof);
      spoof = *node;
      spoof.participant(context.identity());
      spoof.node("rogue-node");
      nd::write_checked(status_writer, &spoof);
      spoofs += 2;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(job ? 1 : 10));
  }
  fmt::print("rogue: sent in others' names to axis {}: {} setpoints, {} feedback, {} faults, {} END_JOB, {} node "
             "statuses\n",
             options.axis, setpoints, feedback, faults, ends, spoofs);
  return job ? 0 : 4;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"netmc_rogue_participant: attacks a netmc DDS domain (integration tests only)"};
  app.require_subcommand(1);
  Options options;
  options.dds.transport = nd::Transport::udp;
  options.dds.name = "rogue";
  for (auto* command : {app.add_subcommand("drive", "Start a job of its own on an idle axis and drive it"),
                        app.add_subcommand("hijack", "Speak for a running job's server and node"),
                        app.add_subcommand("begin", "Begin jobs of its own on an idle axis, reading nothing"),
                        app.add_subcommand("flood", "Send random setpoints to axes as fast as it can")}) {
    command->add_option("--domain", options.dds.domain_id)->check(CLI::Range(0, 230));
    command->add_option("--axis", options.axis)->required();
    command->add_option("--seconds", options.seconds, "Give up after this long");
  }
  auto* drive_command = app.get_subcommand("drive");
  drive_command->add_option("--clock", options.clock)->check(CLI::IsMember({"lockstep", "realtime"}));
  drive_command->add_option("--command", options.command, "The command to send every cycle");
  drive_command->add_flag("--nan", options.nan, "Send NaN commands");
  app.get_subcommand("begin")->add_option("--every", options.every_s, "Seconds between two begins")
      ->check(CLI::Range(0.001, 60.0));
  app.get_subcommand("begin")->add_option("--count", options.begins, "Stop after this many begins")
      ->check(CLI::Range(1, 1000000));
  app.get_subcommand("begin")->add_option("--spec-bytes", options.spec_bytes, "Pad each job spec to this size")
      ->check(CLI::Range(0, 4194304));
  app.get_subcommand("begin")->add_flag("--reading-feedback", options.reading_feedback,
                                        "Read the axis's feedback and events (but write no setpoints)");
  app.get_subcommand("flood")->add_option("--count", options.count, "Setpoints to send")
      ->check(CLI::Range(1, 100000000));
  app.get_subcommand("flood")->add_flag("--control", options.control,
                                        "Job controls (END_ITERATION, END_JOB) instead of setpoints");
  CLI11_PARSE(app, argc, argv);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    if (app.got_subcommand("drive")) return drive(options);
    if (app.got_subcommand("begin")) return begin_without_reader(options);
    if (app.got_subcommand("flood")) return flood(options);
    return hijack(options);
  } catch (const std::exception& error) {
    fmt::print("rogue: error: {}\n", error.what());
    return 1;
  }
}
