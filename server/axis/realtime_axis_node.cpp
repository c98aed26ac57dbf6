#include "server/axis/realtime_axis_node.hpp"

#include <thread>


namespace netmc::axis {

double monotonic_now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

namespace {

std::chrono::steady_clock::time_point at_monotonic(double seconds) {
  return std::chrono::steady_clock::time_point(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(seconds)));
}

}  // namespace

RealtimeAxisNode::RealtimeAxisNode(dds::DdsContext& context, AxisNodeConfig config,
                                   std::chrono::milliseconds watchdog)
    : link_(context, std::move(config)), watchdog_(watchdog) {
  for (const auto id : link_.config().axis_ids) axes_[id] = OwnedAxis{};
}

void RealtimeAxisNode::serve(const std::atomic<bool>& stop) {
  link_.publish_status(netmc::dds::NODE_IDLE, "ready");
  // DDS samples are taken on this thread and handled on the io thread, with the timers.
  std::thread dds_thread([&] {
    while (!stop.load()) {
      if (auto setpoint = link_.setpoints().take(std::chrono::milliseconds(100))) {
        boost::asio::post(io_, [this, s = *setpoint] {
          try {
            handle(s);
          } catch (const std::exception& error) {
            link_.publish_status(netmc::dds::NODE_FAULT,
                           "job " + std::to_string(s.job_id()) + ": " + error.what());
            for (auto& [id, axis] : axes_) axis.endpoint.reset();
          }
        });
      }
    }
  });
  boost::asio::steady_timer status_timer(io_);
  std::function<void()> report = [&] {
    bool running = false, holding = false;
    for (const auto& [id, axis] : axes_) {
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
    status_timer.expires_after(std::chrono::milliseconds(500));
    status_timer.async_wait([&](const boost::system::error_code&) { report(); });
  };
  report();
  io_.run();
  dds_thread.join();
}

void RealtimeAxisNode::handle(const netmc::dds::Setpoint& setpoint) {
  const auto owned = axes_.find(setpoint.axis_id());
  if (owned == axes_.end()) return;
  OwnedAxis& axis = owned->second;
  const std::uint32_t id = setpoint.axis_id();
  switch (setpoint.kind()) {
    case netmc::dds::SETPOINT_BEGIN_ITERATION: {
      if (!setpoint.job_spec().empty()) {
        static_cast<JobAxis&>(axis) = link_.start_job(setpoint);
        axis.timer = std::make_unique<boost::asio::steady_timer>(io_);
      }
      if (!axis.endpoint || axis.job_id != setpoint.job_id()) return;
      axis.endpoint->begin_iteration(setpoint.iteration(), setpoint.start_position_m());
      axis.iteration = setpoint.iteration();
      axis.start_monotonic_s = setpoint.start_monotonic_s();
      axis.next_cycle = 0;
      axis.last_setpoint_s = 0.0;
      axis.holding = false;
      axis.server_send_times.clear();
      schedule(axis, id);
      return;
    }
    case netmc::dds::SETPOINT_COMMAND: {
      if (!axis.endpoint || axis.job_id != setpoint.job_id() || axis.iteration != setpoint.iteration()) return;
      // The setpoint leaves for the actuator now: netsim's downlink delay starts here.
      const double now = monotonic_now_s() - axis.start_monotonic_s;
      axis.endpoint->submit_setpoint(now, setpoint.cycle(), setpoint.command());
      axis.server_send_times[setpoint.cycle()] = setpoint.send_time_s();
      axis.last_setpoint_s = now;
      axis.holding = false;
      return;
    }
    case netmc::dds::SETPOINT_END_ITERATION:
      if (!axis.endpoint || axis.job_id != setpoint.job_id()) return;
      if (axis.timer) axis.timer->cancel();
      axis.next_cycle = axis.cycles;  // stop sampling
      publish_final(id, axis);
      return;
    case netmc::dds::SETPOINT_END_JOB:
      if (axis.job_id == setpoint.job_id()) {
        if (axis.timer) axis.timer->cancel();
        axis.endpoint.reset();
      }
      return;
  }
}

void RealtimeAxisNode::schedule(OwnedAxis& axis, std::uint32_t axis_id) {
  const double t = static_cast<double>(axis.next_cycle) * axis.sample_period_s;
  axis.timer->expires_at(at_monotonic(axis.start_monotonic_s + t));
  axis.timer->async_wait([this, axis_id](const boost::system::error_code& error) {
    if (!error) tick(axis_id);
  });
}

void RealtimeAxisNode::tick(std::uint32_t axis_id) {
  OwnedAxis& axis = axes_.at(axis_id);
  if (!axis.endpoint || axis.next_cycle >= axis.cycles) return;
  const std::uint64_t k = axis.next_cycle;
  const double t = static_cast<double>(k) * axis.sample_period_s;
  netmc::dds::Feedback feedback;
  feedback.axis_id(axis_id);
  feedback.job_id(axis.job_id);
  feedback.iteration(axis.iteration);
  if (k > 0) {
    for (const auto& a : axis.endpoint->advance_to(t)) {
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
  ++axis.next_cycle;
  if (axis.next_cycle < axis.cycles) schedule(axis, axis_id);
}

void RealtimeAxisNode::publish_final(std::uint32_t axis_id, OwnedAxis& axis) {
  netmc::dds::Feedback feedback;
  feedback.axis_id(axis_id);
  feedback.job_id(axis.job_id);
  feedback.iteration(axis.iteration);
  feedback.cycle(axis.cycles);
  feedback.kind(netmc::dds::FEEDBACK_FINAL);
  feedback.lost_setpoints(axis.endpoint->lost_setpoints());
  feedback.stale_setpoints(axis.endpoint->stale_setpoints());
  link_.publish(feedback);
}

}  // namespace netmc::axis
