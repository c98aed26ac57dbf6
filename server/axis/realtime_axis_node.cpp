#include "server/axis/realtime_axis_node.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <thread>

namespace netmc::axis {

RealtimeAxisNode::RealtimeAxisNode(dds::DdsContext& context, AxisNodeConfig config,
                                   std::chrono::milliseconds watchdog)
    : link_(context, std::move(config)), watchdog_(watchdog) {
  for (const auto& axis : link_.config().axes) axes_[axis] = OwnedAxis{};
}

void RealtimeAxisNode::serve(const std::atomic<bool>& stop) {
  link_.publish_status(netmc::dds::NODE_IDLE, "ready");
  // DDS samples are taken on this thread and handled on the io thread, with the timers.
  std::thread dds_thread([&] {
    eprosima::fastdds::dds::WaitSet waitset;
    waitset.attach_condition(link_.control().condition());
    waitset.attach_condition(link_.setpoints().condition());
    while (!stop.load()) {
      while (auto control = link_.control().try_take()) {
        if (link_.hosts(control->axis())) boost::asio::post(io_, [this, c = std::move(*control)] { handle(c); });
      }
      while (auto setpoint = link_.setpoints().try_take()) {
        if (link_.hosts(setpoint->axis())) boost::asio::post(io_, [this, s = *setpoint] { handle(s); });
      }
      eprosima::fastdds::dds::ConditionSeq active;
      waitset.wait(active, eprosima::fastrtps::Duration_t(0, 100'000'000));
    }
  });
  boost::asio::steady_timer status_timer(io_);
  std::function<void()> report = [&] {
    bool running = false, holding = false;
    for (const auto& [name, axis] : axes_) {
      running = running || axis.endpoint != nullptr;
      holding = holding || axis.holding;
    }
    link_.publish_status(holding ? netmc::dds::NODE_HOLD
                           : running ? netmc::dds::NODE_RUNNING : netmc::dds::NODE_IDLE,
                   holding ? "watchdog: no setpoint in time, holding" : running ? "running a job" : "ready");
    if (stop.load()) {
      io_.stop();
      return;
    }
    status_timer.expires_after(kStatusPeriod);
    status_timer.async_wait([&](const boost::system::error_code&) { report(); });
  };
  report();
  io_.run();
  dds_thread.join();
}

void RealtimeAxisNode::handle(const netmc::dds::JobControl& control) {
  const auto owned = axes_.find(control.axis());
  if (owned == axes_.end()) return;
  OwnedAxis& axis = owned->second;
  const std::string& name = owned->first;
  if (const std::string why = link_.admit(control); !why.empty()) {
    if (control.kind() == netmc::dds::CONTROL_BEGIN_ITERATION && !control.job_spec().empty()) {
      link_.refuse(control, netmc::dds::AXIS_REFUSED, why);
    }
    return;
  }
  switch (control.kind()) {
    case netmc::dds::CONTROL_BEGIN_ITERATION: {
      if (!control.job_spec().empty()) {
        if (axis.timer) axis.timer->cancel();
        try {
          static_cast<JobAxis&>(axis) = link_.start_job(control);
        } catch (const std::exception& error) {
          axis.endpoint.reset();
          link_.release(control.server(), control.job_id());
          link_.refuse(control, netmc::dds::AXIS_FAULT, error.what());
          return;
        }
        axis.server = control.server();
        axis.timer = std::make_unique<boost::asio::steady_timer>(io_);
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
      schedule(axis, name);
      return;
    }
    case netmc::dds::CONTROL_END_ITERATION: {
      if (!axis.endpoint || axis.job_id != control.job_id() || axis.iteration != control.iteration()) return;
      // Sampling stops now; the report waits two periods (at least 10 ms), since the last
      // setpoints travel best-effort on another topic and may arrive after this message: they
      // are counted as received, not as missing.
      if (axis.timer) axis.timer->cancel();
      axis.running = false;
      axis.ending = true;
      const auto grace = std::max(std::chrono::duration<double>(2.0 * axis.sample_period_s),
                                  std::chrono::duration<double>(0.010));
      axis.timer->expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(grace));
      axis.timer->async_wait([this, name, iteration = axis.iteration, sent = control.cycle()](
                                 const boost::system::error_code& error) {
        OwnedAxis& ending = axes_.at(name);
        if (error || !ending.endpoint || !ending.ending || ending.iteration != iteration) return;
        end_iteration(name, ending, sent);
      });
      return;
    }
    case netmc::dds::CONTROL_END_JOB:
      if (axis.job_id == control.job_id()) {
        if (axis.timer) axis.timer->cancel();
        axis.endpoint.reset();
        axis.running = false;
        axis.ending = false;
        axis.holding = false;
        link_.release(control.server(), control.job_id());
      }
      return;
  }
}

void RealtimeAxisNode::handle(const netmc::dds::Setpoint& setpoint) {
  const auto owned = axes_.find(setpoint.axis());
  if (owned == axes_.end()) return;
  OwnedAxis& axis = owned->second;
  if (!axis.endpoint || !(axis.running || axis.ending) || axis.job_id != setpoint.job_id() ||
      axis.iteration != setpoint.iteration() || !link_.from_holder(setpoint.server(), setpoint.job_id())) {
    return;
  }
  if (axis.ending) {  // arrived after the iteration's end: late, but not lost
    ++axis.commands_received;
    return;
  }
  // Nothing but a finite command of this job's cycles reaches the plant.
  if (!std::isfinite(setpoint.command()) || !std::isfinite(setpoint.send_time_s()) ||
      setpoint.cycle() >= axis.cycles) {
    return;
  }
  // The setpoint leaves for the actuator now: netsim's downlink delay starts here.
  const double now = link_.now_s() - axis.start_time_s;
  axis.endpoint->submit_setpoint(now, setpoint.cycle(), setpoint.command());
  axis.server_send_times[setpoint.cycle()] = setpoint.send_time_s();
  axis.last_setpoint_s = now;
  axis.holding = false;
  ++axis.commands_received;
}

void RealtimeAxisNode::schedule(OwnedAxis& axis, const std::string& axis_name) {
  const double t = static_cast<double>(axis.next_cycle) * axis.sample_period_s;
  axis.timer->expires_at(dds::steady_time_at(link_.config().time_base, axis.start_time_s + t));
  axis.timer->async_wait([this, axis_name](const boost::system::error_code& error) {
    if (!error) tick(axis_name);
  });
}

void RealtimeAxisNode::tick(const std::string& axis_name) {
  OwnedAxis& axis = axes_.at(axis_name);
  if (!axis.endpoint || !axis.running || axis.next_cycle >= axis.cycles) return;
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
  set_sample(feedback, k, t, axis.endpoint->sample());
  feedback.lost_setpoints(axis.endpoint->lost_setpoints());
  feedback.stale_setpoints(axis.endpoint->stale_setpoints());
  link_.publish(feedback);
  ++axis.samples;
  ++axis.next_cycle;
  if (axis.next_cycle < axis.cycles) schedule(axis, axis_name);
}

void RealtimeAxisNode::end_iteration(const std::string& axis_name, OwnedAxis& axis,
                                     std::uint64_t commands_sent) {
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
  event.missing_setpoints(commands_sent > axis.commands_received ? commands_sent - axis.commands_received : 0);
  link_.publish_event(event);
}

}  // namespace netmc::axis
