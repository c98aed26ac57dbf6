#include "server/axis/lockstep_axis_node.hpp"

namespace netmc::axis {

using netmc::dds::Feedback;
using netmc::dds::Setpoint;

LockstepAxisNode::LockstepAxisNode(dds::DdsContext& context, AxisNodeConfig config)
    : link_(context, std::move(config)) {
  for (const auto id : link_.config().axis_ids) axes_[id] = JobAxis{};
}

void LockstepAxisNode::serve(const std::atomic<bool>& stop) {
  link_.publish_status(netmc::dds::NODE_IDLE, "ready");
  auto last_status = std::chrono::steady_clock::now();
  while (!stop.load()) {
    if (auto setpoint = link_.setpoints().take(std::chrono::milliseconds(200))) {
      try {
        handle(*setpoint);
      } catch (const std::exception& error) {
        // A job this node cannot run must not take the node down: report it and stay ready.
        link_.publish_status(netmc::dds::NODE_FAULT, "job " + std::to_string(setpoint->job_id()) +
                                                         ": " + error.what());
        for (auto& [id, axis] : axes_) axis.endpoint.reset();
      }
    }
    if (std::chrono::steady_clock::now() - last_status > std::chrono::seconds(1)) {
      bool running = false;
      for (const auto& [id, axis] : axes_) running = running || axis.endpoint != nullptr;
      link_.publish_status(running ? netmc::dds::NODE_RUNNING : netmc::dds::NODE_IDLE,
                           running ? "running a job" : "ready");
      last_status = std::chrono::steady_clock::now();
    }
  }
}

void LockstepAxisNode::handle(const Setpoint& setpoint) {
  const auto owned = axes_.find(setpoint.axis_id());
  if (owned == axes_.end()) return;  // another node's axis
  JobAxis& axis = owned->second;
  if (setpoint.kind() == netmc::dds::SETPOINT_BEGIN_ITERATION && !setpoint.job_spec().empty()) {
    axis = link_.start_job(setpoint);
  }
  if (!axis.endpoint || axis.job_id != setpoint.job_id()) return;

  Feedback feedback;
  feedback.axis_id(setpoint.axis_id());
  feedback.job_id(setpoint.job_id());
  feedback.iteration(setpoint.iteration());
  switch (setpoint.kind()) {
    case netmc::dds::SETPOINT_BEGIN_ITERATION:
      axis.endpoint->begin_iteration(setpoint.iteration(), setpoint.start_position_m());
      set_sample(feedback, 0, 0.0, axis.endpoint->sample());
      break;
    case netmc::dds::SETPOINT_COMMAND: {
      axis.endpoint->submit_setpoint(setpoint.send_time_s(), setpoint.cycle(), setpoint.command());
      const std::uint64_t next = setpoint.cycle() + 1;
      if (next >= axis.cycles) {
        feedback.cycle(next);
        feedback.kind(netmc::dds::FEEDBACK_FINAL);
        break;
      }
      const double next_time = static_cast<double>(next) * axis.sample_period_s;
      append_applied(feedback, axis.endpoint->advance_to(next_time));
      set_sample(feedback, next, next_time, axis.endpoint->sample());
      break;
    }
    case netmc::dds::SETPOINT_END_ITERATION:
      feedback.cycle(setpoint.cycle());
      feedback.kind(netmc::dds::FEEDBACK_FINAL);
      break;
    case netmc::dds::SETPOINT_END_JOB:
      axis.endpoint.reset();
      return;
  }
  feedback.lost_setpoints(axis.endpoint->lost_setpoints());
  feedback.stale_setpoints(axis.endpoint->stale_setpoints());
  link_.publish(feedback);
}

}  // namespace netmc::axis
