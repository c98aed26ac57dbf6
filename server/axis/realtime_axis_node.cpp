#include "server/axis/realtime_axis_node.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "server/realtime/realtime_scheduling.hpp"

namespace netmc::axis {
namespace {

// Longest sleep of the loop: how soon it sees a stop request with nothing else to do.
constexpr std::chrono::milliseconds kIdleWake{100};

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const auto index = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index), values.end());
  return values[index];
}

}  // namespace

RealtimeAxisNode::RealtimeAxisNode(dds::DdsContext& context, AxisNodeConfig config,
                                   std::chrono::milliseconds watchdog)
    : link_(context, std::move(config)), watchdog_(watchdog) {
  for (const auto& axis : link_.config().axes) axes_[axis] = OwnedAxis{};
}

void RealtimeAxisNode::serve(const std::atomic<bool>& stop) {
  realtime::tighten_timer_slack();
  eprosima::fastdds::dds::WaitSet waitset;
  waitset.attach_condition(link_.control().condition());
  waitset.attach_condition(link_.setpoints().condition());
  auto next_status = Clock::now();
  while (!stop.load()) {
    link_.poll_fault_reset();
    const auto now = Clock::now();
    // Due samples first: a sample is taken at its time, then the setpoints that came meanwhile
    // are applied (on arrival, as they would be anyway: after the sample instant).
    for (auto& [name, axis] : axes_) {
      if (sampling(axis) && axis.next_sample <= now) sample(name, axis, now);
      if (axis.ending && axis.report_at <= now) end_iteration(name, axis);
    }
    while (auto setpoint = link_.take_setpoint()) handle(*setpoint);
    while (auto control = link_.take_control()) handle(*control);
    if (now >= next_status) {
      publish_status();
      next_status = now + kStatusPeriod;
    }
    auto wake = std::min(next_status, Clock::now() + kIdleWake);
    for (const auto& [name, axis] : axes_) {
      if (sampling(axis)) wake = std::min(wake, axis.next_sample);
      if (axis.ending) wake = std::min(wake, axis.report_at);
    }
    const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(wake - Clock::now()).count();
    if (left > 0) {
      eprosima::fastdds::dds::ConditionSeq active;
      waitset.wait(active, eprosima::fastrtps::Duration_t(static_cast<int32_t>(left / 1'000'000'000),
                                                          static_cast<uint32_t>(left % 1'000'000'000)));
    }
  }
}

void RealtimeAxisNode::publish_status() {
  bool running = false, holding = false;
  for (const auto& [name, axis] : axes_) {
    running = running || axis.endpoint != nullptr;
    holding = holding || axis.holding;
  }
  link_.publish_status(holding ? netmc::dds::NODE_HOLD
                       : running ? netmc::dds::NODE_RUNNING : netmc::dds::NODE_IDLE,
                       holding ? "watchdog: no setpoint in time, holding" : running ? "running a job" : "ready");
}

void RealtimeAxisNode::handle(const netmc::dds::JobControl& control) {
  const auto owned = axes_.find(control.axis());
  if (owned == axes_.end()) return;
  OwnedAxis& axis = owned->second;
  if (const std::string why = link_.admit(control); !why.empty()) {
    if (control.kind() == netmc::dds::CONTROL_BEGIN_ITERATION && !control.job_spec().empty()) {
      link_.refuse(control, netmc::dds::AXIS_REFUSED, why);
    }
    return;
  }
  switch (control.kind()) {
    case netmc::dds::CONTROL_BEGIN_ITERATION: {
      if (!control.job_spec().empty()) {
        try {
          static_cast<JobAxis&>(axis) = link_.start_job(control);
        } catch (const std::exception& error) {
          axis.endpoint.reset();
          axis.running = axis.ending = false;
          link_.release(control.axis(), control.server(), control.job_id());
          link_.refuse(control, netmc::dds::AXIS_FAULT, error.what());
          return;
        }
        axis.server = control.server();
      }
      if (!axis.endpoint || axis.job_id != control.job_id() || !std::isfinite(control.start_time_s()) ||
          !std::isfinite(control.start_position_m())) {
        return;
      }
      axis.endpoint->begin_iteration(control.iteration(), control.start_position_m());
      axis.iteration = control.iteration();
      axis.start_time_s = control.start_time_s();
      axis.next_cycle = 0;
      axis.last_setpoint_s = 0.0;
      axis.holding = false;
      axis.running = true;
      axis.ending = false;
      axis.samples = 0;
      axis.commands_received = 0;
      axis.server_send_times.clear();
      axis.feedback_sent.assign(axis.cycles, Clock::time_point{});
      axis.newest_timed = -1;
      axis.round_trips_s.clear();
      axis.wake_late_s.clear();
      axis.round_trips_s.reserve(axis.cycles);
      axis.wake_late_s.reserve(axis.cycles);
      schedule(axis);
      return;
    }
    case netmc::dds::CONTROL_END_ITERATION: {
      if (!axis.endpoint || axis.job_id != control.job_id() || axis.iteration != control.iteration()) return;
      // Sampling stops now; the report waits two periods (at least 10 ms), since the last
      // setpoints travel best-effort on another topic and may arrive after this message: they
      // are counted as received, not as missing.
      axis.running = false;
      axis.ending = true;
      axis.commands_sent = control.cycle();
      const auto grace = std::max(std::chrono::duration<double>(2.0 * axis.sample_period_s),
                                  std::chrono::duration<double>(0.010));
      axis.report_at = Clock::now() + std::chrono::duration_cast<Clock::duration>(grace);
      return;
    }
    case netmc::dds::CONTROL_END_JOB:
      if (axis.job_id == control.job_id()) {
        axis.endpoint.reset();
        axis.running = false;
        axis.ending = false;
        axis.holding = false;
        link_.release(control.axis(), control.server(), control.job_id());
        publish_status();  // at once: a server deciding on these axes must not see a stale hold
      }
      return;
  }
}

void RealtimeAxisNode::handle(const netmc::dds::Setpoint& setpoint) {
  const auto owned = axes_.find(setpoint.axis());
  if (owned == axes_.end()) return;
  OwnedAxis& axis = owned->second;
  if (!axis.endpoint || !(axis.running || axis.ending) || axis.job_id != setpoint.job_id() ||
      axis.iteration != setpoint.iteration() ||
      !link_.from_holder(setpoint.axis(), setpoint.server(), setpoint.job_id())) {
    return;
  }
  if (axis.ending) {  // arrived after the iteration's end: late, but not lost
    ++axis.commands_received;
    return;
  }
  // Nothing but a setpoint of this job's cycles is looked at; the actuator trips on a command it
  // must not take (non-finite, beyond its limit) when it applies it (reported with the sample).
  if (!std::isfinite(setpoint.send_time_s()) || setpoint.cycle() >= axis.cycles) return;
  const auto arrived = Clock::now();
  const auto cycle = static_cast<std::int64_t>(setpoint.cycle());
  if (cycle > axis.newest_timed && axis.feedback_sent[setpoint.cycle()] != Clock::time_point{}) {
    axis.round_trips_s.push_back(std::chrono::duration<double>(arrived - axis.feedback_sent[setpoint.cycle()]).count());
    axis.newest_timed = cycle;
  }
  // The setpoint leaves for the actuator now: netsim's downlink delay starts here.
  const double now = link_.now_s() - axis.start_time_s;
  axis.endpoint->submit_setpoint(now, setpoint.cycle(), setpoint.command());
  axis.server_send_times[setpoint.cycle()] = setpoint.send_time_s();
  axis.last_setpoint_s = now;
  axis.holding = false;
  ++axis.commands_received;
}

void RealtimeAxisNode::schedule(OwnedAxis& axis) const {
  const double t = static_cast<double>(axis.next_cycle) * axis.sample_period_s;
  axis.next_sample = dds::steady_time_at(link_.config().time_base, axis.start_time_s + t);
}

void RealtimeAxisNode::sample(const std::string& axis_name, OwnedAxis& axis, Clock::time_point now) {
  axis.wake_late_s.push_back(std::chrono::duration<double>(now - axis.next_sample).count());
  const std::uint64_t k = axis.next_cycle;
  const double t = static_cast<double>(k) * axis.sample_period_s;
  netmc::dds::Feedback feedback;
  feedback.axis(axis_name);
  feedback.server(axis.server);
  feedback.job_id(axis.job_id);
  feedback.iteration(axis.iteration);
  if (k > 0) {
    for (const auto& a : axis.endpoint->advance_to(t)) {
      if (feedback.applied().size() >= netmc::dds::kMaxApplied) break;
      netmc::dds::AppliedSetpoint applied;
      applied.cycle(a.sequence);
      const auto sent = axis.server_send_times.find(a.sequence);  // see server_send_times
      applied.send_time_s(sent != axis.server_send_times.end() ? sent->second : a.send_time_s);
      applied.arrival_time_s(a.arrival_time_s);
      feedback.applied().push_back(applied);
    }
    // Setpoints older than the newest applied one can no longer act.
    if (!feedback.applied().empty()) {
      axis.server_send_times.erase(axis.server_send_times.begin(),
                                   axis.server_send_times.upper_bound(feedback.applied().back().cycle()));
    }
  }
  // Watchdog: a running axis without setpoints stands still rather than keep the last command.
  if (k > 0 && t - axis.last_setpoint_s > std::chrono::duration<double>(watchdog_).count()) {
    axis.endpoint->hold();
    axis.holding = true;
  }
  link_.report_fault(axis_name, axis, axis.server, axis.iteration);
  set_sample(feedback, k, t, axis.endpoint->sample());
  feedback.lost_setpoints(axis.endpoint->lost_setpoints());
  feedback.stale_setpoints(axis.endpoint->stale_setpoints());
  link_.publish(feedback);
  axis.feedback_sent[k] = Clock::now();
  ++axis.samples;
  ++axis.next_cycle;
  if (axis.next_cycle < axis.cycles) schedule(axis);
}

void RealtimeAxisNode::end_iteration(const std::string& axis_name, OwnedAxis& axis) {
  axis.ending = false;
  netmc::dds::AxisEvent event;
  event.axis(axis_name);
  event.server(axis.server);
  event.job_id(axis.job_id);
  event.iteration(axis.iteration);
  event.kind(netmc::dds::AXIS_ITERATION_ENDED);
  event.samples(axis.samples);
  event.lost_setpoints(axis.endpoint->lost_setpoints());
  event.stale_setpoints(axis.endpoint->stale_setpoints());
  event.missing_setpoints(axis.commands_sent > axis.commands_received ? axis.commands_sent - axis.commands_received
                                                                      : 0);
  link_.publish_event(event);
  // The node's own view of the loop's timing, for the operator and bench/realtime_sweep.sh.
  const double us = 1e6;
  spdlog::info("axis {} job {} iteration {}: {} samples, sample wake-up late p50 {:.0f} us "
                   "p99 {:.0f} us; round trip feedback->setpoint p50 {:.0f} us p99 {:.0f} us max {:.0f} us ({} "
                   "setpoints)",
                   axis_name, axis.job_id, axis.iteration, axis.samples,
                   percentile(axis.wake_late_s, 0.50) * us, percentile(axis.wake_late_s, 0.99) * us,
                   percentile(axis.round_trips_s, 0.50) * us, percentile(axis.round_trips_s, 0.99) * us,
                   axis.round_trips_s.empty() ? 0.0 : *std::max_element(axis.round_trips_s.begin(), axis.round_trips_s.end()) * us,
                   axis.round_trips_s.size());
}

}  // namespace netmc::axis
