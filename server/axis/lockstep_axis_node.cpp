#include "server/axis/lockstep_axis_node.hpp"

#include <cmath>
#include <iostream>

namespace netmc::axis {

using netmc::dds::Feedback;

LockstepAxisNode::LockstepAxisNode(dds::DdsContext& context, AxisNodeConfig config)
    : link_(context, std::move(config)) {
  for (const auto& axis : link_.config().axes) axes_[axis] = JobAxis{};
}

void LockstepAxisNode::serve(const std::atomic<bool>& stop) {
  link_.publish_status(netmc::dds::NODE_IDLE, "ready");
  eprosima::fastdds::dds::WaitSet waitset;
  waitset.attach_condition(link_.control_arrived());
  waitset.attach_condition(link_.setpoint_arrived());
  auto last_status = std::chrono::steady_clock::now();
  while (!stop.load()) {
    reset_faults(link_.poll_fault_reset());
    while (auto control = link_.take_control()) handle(*control);
    settle_starts();
    while (auto setpoint = link_.take_setpoint()) handle(*setpoint);
    if (std::chrono::steady_clock::now() - last_status >= kStatusPeriod) {
      publish_status();
      last_status = std::chrono::steady_clock::now();
    }
    const auto wait = starts_.empty() ? std::chrono::milliseconds(100) : PendingJobStarts::kLookPeriod;
    eprosima::fastdds::dds::ConditionSeq active;
    waitset.wait(active, eprosima::fastrtps::Duration_t(0, static_cast<std::uint32_t>(wait.count() * 1'000'000)));
  }
}

void LockstepAxisNode::publish_status() {
  bool running = false;
  for (const auto& [name, axis] : axes_) {
    running = running || axis.endpoint != nullptr;
    report_drive(name);
  }
  link_.publish_status(running ? netmc::dds::NODE_RUNNING : netmc::dds::NODE_IDLE, running ? "running a job" : "ready");
}

void LockstepAxisNode::report_drive(const std::string& axis_name) {
  const JobAxis& axis = axes_.at(axis_name);
  link_.report_motion(axis_name, axis.endpoint ? "job" : "off", 0.0);
  if (axis.endpoint) {
    link_.report_drive(axis_name, axis.endpoint->supervised().power_state(), axis.endpoint->supervised().reading());
    return;
  }
  const auto drive = drives_.find(axis_name);
  if (drive == drives_.end()) return;
  const drive::DriveFeedback feedback = drive->second->read();
  auto state = drive::decode_statusword(feedback.statusword).value_or(drive::PowerState::not_ready_to_switch_on);
  if (link_.faulted(axis_name)) state = drive::PowerState::fault;
  link_.report_drive(axis_name, state, feedback);
}

void LockstepAxisNode::report_fault(const std::string& axis_name, JobAxis& axis, const std::string& server,
                                    std::uint32_t iteration) {
  if (!axis.endpoint || !axis.endpoint->fault() || axis.fault_reported) return;
  link_.report_fault(axis_name, axis, server, iteration);
  // Virtual time stops with the job: the drive's reaction to the trip ends now.
  axis.endpoint->supervised().finish_reaction();
  report_drive(axis_name);
}

void LockstepAxisNode::reset_faults(const std::vector<std::string>& axes) {
  for (const auto& name : axes) {
    JobAxis& axis = axes_.at(name);
    if (axis.endpoint) {
      axis.endpoint->supervised().clear_fault();
    } else if (const auto drive = drives_.find(name); drive != drives_.end()) {
      drive::reset_drive_fault(*drive->second);
    }
    report_drive(name);
  }
}

void LockstepAxisNode::handle(const netmc::dds::JobControl& control) {
  const auto owned = axes_.find(control.axis());
  if (owned == axes_.end()) return;  // another node's axis
  if (link_.reset_request(control)) {
    link_.reset_faults({control.axis()});
    reset_faults({control.axis()});
    return;
  }
  if (link_.commissioning_request(control)) {
    // Lockstep axes are simulated in the job's virtual time: nothing stands still to be moved.
    link_.report_command(control.axis(), control.job_id(), true,
                         "node " + link_.config().node +
                             " runs lockstep: its simulated axes take no commissioning (a realtime node's hardware "
                             "drive does)");
    publish_status();
    return;
  }
  if (control.kind() == netmc::dds::CONTROL_PREPARE_ITERATION) return;  // realtime servers only
  if (starts_.waiting(control.axis())) {
    starts_.hold_back(control);
    return;
  }
  if (const std::string why = link_.admit(control); !why.empty()) {
    if (control.kind() == netmc::dds::CONTROL_BEGIN_ITERATION && !control.job_spec().empty()) {
      link_.refuse(control, netmc::dds::AXIS_REFUSED, why);
    }
    return;
  }
  JobAxis& axis = owned->second;
  if (control.kind() == netmc::dds::CONTROL_BEGIN_ITERATION && !control.job_spec().empty()) {
    if (!link_.linked_to_server(control)) {  // handled again once it does
      starts_.wait(control, std::chrono::steady_clock::now());
      return;
    }
    try {
      axis = link_.start_job(control);
    } catch (const std::exception& error) {
      refuse_start(control, error.what());
      return;
    }
    drives_[control.axis()] = axis.endpoint->supervised().shared_drive();
  }
  if (!axis.endpoint || axis.job_id != control.job_id()) return;

  Feedback feedback;
  feedback.axis(control.axis());
  feedback.server(control.server());
  feedback.job_id(control.job_id());
  feedback.iteration(control.iteration());
  switch (control.kind()) {
    case netmc::dds::CONTROL_BEGIN_ITERATION:
      axis.endpoint->begin_iteration(control.iteration(), control.start_position_m());
      set_sample(feedback, 0, 0.0, axis.endpoint->sample());
      break;
    case netmc::dds::CONTROL_END_ITERATION:
      feedback.cycle(control.cycle());
      feedback.kind(netmc::dds::FEEDBACK_FINAL);
      break;
    case netmc::dds::CONTROL_END_JOB:
      if (axis.endpoint->supervised().power_state() == drive::PowerState::operation_enabled) {
        axis.endpoint->supervised().drive().write_controlword(drive::controlword::shutdown);
      }
      axis.endpoint.reset();
      link_.release(control.axis(), control.server(), control.job_id());
      publish_status();  // at once: a server deciding on these axes must not see a stale hold
      return;
    case netmc::dds::CONTROL_PREPARE_ITERATION:
    case netmc::dds::CONTROL_FAULT_RESET:
    case netmc::dds::CONTROL_ENABLE:
    case netmc::dds::CONTROL_DISABLE:
    case netmc::dds::CONTROL_QUICK_STOP:
    case netmc::dds::CONTROL_MOVE:
    case netmc::dds::CONTROL_JOG:
      return;
  }
  set_downlink_counters(feedback, *axis.endpoint);
  link_.publish(feedback);
}

void LockstepAxisNode::refuse_start(const netmc::dds::JobControl& control, const std::string& why) {
  axes_.at(control.axis()) = JobAxis{};
  link_.release(control.axis(), control.server(), control.job_id());
  link_.refuse(control, netmc::dds::AXIS_FAULT, why);
  link_.publish_status(netmc::dds::NODE_FAULT, "job " + std::to_string(control.job_id()) + ": " + why);
}

void LockstepAxisNode::settle_starts() {
  if (starts_.empty()) return;
  const auto linked = [this](const netmc::dds::JobControl& begin) { return link_.linked_to_server(begin); };
  const auto settled = starts_.settle(linked, std::chrono::steady_clock::now());
  for (const auto& start : settled) {
    if (start.linked) {
      handle(start.begin);
    } else {
      refuse_start(start.begin, link_.why_not_linked(start.begin));
    }
    for (const auto& control : start.held_back) handle(control);
  }
}

void LockstepAxisNode::handle(const netmc::dds::Setpoint& setpoint) {
  const auto owned = axes_.find(setpoint.axis());
  if (owned == axes_.end()) return;
  JobAxis& axis = owned->second;
  if (!axis.endpoint || axis.job_id != setpoint.job_id() || !link_.from_holder(setpoint.axis(), setpoint.server(), setpoint.job_id())) {
    return;
  }
  // Nothing but a setpoint of this job's cycles is looked at; the actuator trips on a command it
  // must not take (non-finite, beyond its limit) when it applies it.
  if (!std::isfinite(setpoint.send_time_s()) || setpoint.cycle() >= axis.cycles) return;
  Feedback feedback;
  feedback.axis(setpoint.axis());
  feedback.server(setpoint.server());
  feedback.job_id(setpoint.job_id());
  feedback.iteration(setpoint.iteration());
  submit_to(*axis.endpoint, setpoint.send_time_s(), setpoint);
  const std::uint64_t next = setpoint.cycle() + 1;
  if (next >= axis.cycles) {
    feedback.cycle(next);
    feedback.kind(netmc::dds::FEEDBACK_FINAL);
  } else {
    const double next_time = static_cast<double>(next) * axis.sample_period_s;
    append_applied(feedback, axis.endpoint->advance_to(next_time));
    set_sample(feedback, next, next_time, axis.endpoint->sample());
  }
  set_downlink_counters(feedback, *axis.endpoint);
  report_fault(setpoint.axis(), axis, setpoint.server(), setpoint.iteration());  // before the sample
  link_.publish(feedback);
}

}  // namespace netmc::axis
