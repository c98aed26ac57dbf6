#include "server/axis/realtime_axis_node.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "server/realtime/realtime_scheduling.hpp"

namespace netmc::axis {
namespace {

// Longest sleep of the loop: how soon it sees a stop request with nothing else to do.
constexpr std::chrono::milliseconds kIdleWake{100};
// How often a hardware drive is written while it moves (CSP targets), read while it holds or
// ramps, and read while idle.
constexpr std::chrono::milliseconds kMovePoll{2};
constexpr std::chrono::milliseconds kHoldPoll{10};
constexpr std::chrono::milliseconds kIdlePoll{500};
// Consecutive reads inside the tolerance that make a positioned axis settled.
constexpr int kSettledReads = 3;
// How long the operator's reset of a drive that does not answer is tried again.
constexpr std::chrono::seconds kResetRetry{5};

// Feedback send times kept for timing round trips: 4 s at 1 kHz, far beyond any watchdog.
constexpr std::size_t kFeedbackTimes = 4096;
// Setpoints in flight whose server send time is kept (tau_ca); more is not a loop but a flood.
constexpr std::size_t kMaxSetpointsInFlight = 4096;

const char* control_kind_name(netmc::dds::ControlKind kind) {
  switch (kind) {
    case netmc::dds::CONTROL_ENABLE: return "enable";
    case netmc::dds::CONTROL_DISABLE: return "disable";
    case netmc::dds::CONTROL_QUICK_STOP: return "quick stop";
    case netmc::dds::CONTROL_MOVE: return "move";
    case netmc::dds::CONTROL_JOG: return "jog";
    default: return "job control";
  }
}

bool ramping(drive::PowerState state) {
  return state == drive::PowerState::quick_stop_active || state == drive::PowerState::fault_reaction_active;
}

}  // namespace

RealtimeAxisNode::RealtimeAxisNode(dds::DdsContext& context, AxisNodeConfig config,
                                   std::chrono::milliseconds watchdog)
    : link_(context, std::move(config)), watchdog_(watchdog) {
  for (const auto& axis : link_.config().axes) {
    OwnedAxis owned;
    owned.drive = link_.config().drives.at(axis).hardware;
    owned.applied_since_sample.reserve(netmc::dds::kMaxApplied);
    if (owned.drive && !owned.drive->virtual_time()) {
      const auto& positioning = link_.config().positioning;
      CommissioningSettings settings;
      settings.velocity_m_s = positioning.velocity_m_s;
      settings.acceleration_m_s2 = positioning.acceleration_m_s2;
      owned.commissioning.emplace(settings, link_.config().drives.at(axis).limits);
    }
    axes_.emplace(axis, std::move(owned));
  }
}

void RealtimeAxisNode::serve(const std::atomic<bool>& stop) {
  realtime::tighten_timer_slack();
  eprosima::fastdds::dds::WaitSet waitset;
  waitset.attach_condition(link_.control_arrived());
  waitset.attach_condition(link_.setpoint_arrived());
  auto next_status = Clock::now();
  while (!stop.load()) {
    reset_faults(link_.poll_fault_reset());
    const auto now = Clock::now();
    // Due samples first: a sample is taken at its time, then the setpoints that came meanwhile
    // are applied (on arrival, as they would be anyway: after the sample instant).
    for (auto& [name, axis] : axes_) {
      if (sampling(axis) && axis.next_sample <= now) sample(name, axis, now);
      if (axis.report_due && axis.report_at <= now) end_iteration(name, axis);
      if (hardware(axis) && axis.phase == Phase::running && axis.endpoint) {
        // Setpoints the emulated downlink delayed act when they arrive.
        const auto arrival = axis.endpoint->next_arrival_s();
        const double job_now = link_.now_s() - axis.start_time_s;
        if (arrival && *arrival <= job_now) {
          for (const auto& a : axis.endpoint->apply_arrived(job_now)) axis.applied_since_sample.push_back(a);
        }
      }
      if (polled(axis) && axis.next_poll <= now) poll(name, axis, now);
    }
    while (auto setpoint = link_.take_setpoint()) handle(*setpoint);
    while (auto control = link_.take_control()) handle(*control);
    settle_starts();
    if (now >= next_status) {
      publish_status();
      next_status = now + kStatusPeriod;
    }
    const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(wake_time(next_status) - Clock::now()).count();
    if (left > 0) {
      eprosima::fastdds::dds::ConditionSeq active;
      waitset.wait(active, eprosima::fastrtps::Duration_t(static_cast<int32_t>(left / 1'000'000'000),
                                                          static_cast<uint32_t>(left % 1'000'000'000)));
    }
  }
}

RealtimeAxisNode::Clock::time_point RealtimeAxisNode::wake_time(Clock::time_point next_status) const {
  auto wake = std::min(next_status, Clock::now() + (starts_.empty() ? kIdleWake : PendingJobStarts::kLookPeriod));
  for (const auto& [name, axis] : axes_) {
    if (sampling(axis)) wake = std::min(wake, axis.next_sample);
    if (axis.report_due) wake = std::min(wake, axis.report_at);
    if (polled(axis)) wake = std::min(wake, axis.next_poll);
    if (!hardware(axis)) continue;
    if (axis.phase == Phase::running && axis.endpoint) {
      if (const auto arrival = axis.endpoint->next_arrival_s()) {
        wake = std::min(wake, dds::steady_time_at(link_.config().time_base, axis.start_time_s + *arrival));
      }
    }
  }
  return wake;
}

void RealtimeAxisNode::publish_status() {
  bool running = false, holding = false;
  for (auto& [name, axis] : axes_) {
    running = running || axis.endpoint != nullptr;
    holding = holding || axis.holding;
    report_drive(name, axis);
  }
  link_.publish_status(holding ? netmc::dds::NODE_HOLD
                       : running ? netmc::dds::NODE_RUNNING : netmc::dds::NODE_IDLE,
                       holding ? "watchdog: no setpoint in time, quick stop" : running ? "running a job" : "ready");
}

// What the node last saw of the axis's drive: the job's supervision while there is one, else a
// read of the drive itself (hardware: done by poll; a simulated drive: its state).
void RealtimeAxisNode::report_drive(const std::string& axis_name, OwnedAxis& axis) {
  report_motion(axis_name, axis);
  drive::PowerState state = drive::PowerState::not_ready_to_switch_on;
  drive::DriveFeedback feedback;
  if (axis.endpoint) {
    state = axis.endpoint->supervised().power_state();
    feedback = axis.endpoint->supervised().reading();
  } else if (axis.drive && axis.drive->virtual_time()) {
    feedback = axis.drive->read();
    state = drive::decode_statusword(feedback.statusword).value_or(state);
  } else {
    return;  // hardware without a job: poll reports it
  }
  if (link_.faulted(axis_name) && state != drive::PowerState::fault) {
    state = ramping(state) || state == drive::PowerState::operation_enabled ? drive::PowerState::fault_reaction_active
                                                                             : drive::PowerState::fault;
  }
  link_.report_drive(axis_name, state, feedback);
  if (state != axis.reported_state) {
    axis.reported_state = state;
    spdlog::info("axis {}: {}", axis_name, drive::power_state_name(state));
    link_.publish_status(axis.holding ? netmc::dds::NODE_HOLD
                         : axis.endpoint ? netmc::dds::NODE_RUNNING : netmc::dds::NODE_IDLE,
                         std::string("axis ") + axis_name + ": " + drive::power_state_name(state));
  }
}

void RealtimeAxisNode::report_motion(const std::string& axis_name, const OwnedAxis& axis) {
  const bool commissioned = !axis.endpoint && axis.commissioning && axis.commissioning->active();
  const char* motion = axis.endpoint                 ? "job"
                       : commissioned                ? motion_name(axis.commissioning->motion())
                       : axis.phase == Phase::stopping ? "stopping"
                                                       : "off";
  link_.report_motion(axis_name, motion, commissioned ? axis.commissioning->following_error_m() : 0.0);
  link_.report_command(axis_name, axis.command_number, !axis.command_refusal.empty(),
                       !axis.command_refusal.empty() ? axis.command_refusal
                       : axis.commissioning          ? axis.commissioning->note()
                                                     : std::string());
}

void RealtimeAxisNode::reset_faults(const std::vector<std::string>& axes) {
  for (const auto& name : axes) {
    OwnedAxis& axis = axes_.at(name);
    if (axis.endpoint) axis.endpoint->supervised().clear_fault();
    // The drive's own fault: reset now, or (a drive not reachable yet) at the next polls.
    axis.reset_until = Clock::now() + kResetRetry;
    reset_drive(name, axis);
    axis.next_poll = Clock::now();
    report_drive(name, axis);
  }
}

void RealtimeAxisNode::reset_drive(const std::string& axis_name, OwnedAxis& axis) {
  if (Clock::now() >= axis.reset_until || !axis.drive) return;
  try {
    drive::reset_drive_fault(*axis.drive);
    axis.reset_until = {};
  } catch (const drive::DriveError& error) {
    if (!hardware(axis)) axis.reset_until = {};
    spdlog::warn("axis {}: the drive's fault reset failed: {}{}", axis_name, error.what(),
                 hardware(axis) ? " (tried again while the drive is polled, for 5 s)" : "");
  }
}

void RealtimeAxisNode::handle(const netmc::dds::JobControl& control) {
  const auto owned = axes_.find(control.axis());
  if (owned == axes_.end()) return;
  OwnedAxis& axis = owned->second;
  if (link_.reset_request(control)) {
    spdlog::info("axis {}: fault reset asked by server {}", control.axis(), control.server());
    link_.reset_faults({control.axis()});
    reset_faults({control.axis()});
    return;
  }
  if (link_.commissioning_request(control)) {
    commission(owned->first, axis, control);
    return;
  }
  if (starts_.waiting(control.axis())) {
    starts_.hold_back(control);
    return;
  }
  if (const std::string why = link_.admit(control); !why.empty()) {
    if ((control.kind() == netmc::dds::CONTROL_BEGIN_ITERATION ||
         control.kind() == netmc::dds::CONTROL_PREPARE_ITERATION) &&
        !control.job_spec().empty()) {
      link_.refuse(control, netmc::dds::AXIS_REFUSED, why);
    }
    return;
  }
  axis.last_contact = Clock::now();
  switch (control.kind()) {
    case netmc::dds::CONTROL_PREPARE_ITERATION:
      prepare(owned->first, axis, control);
      return;
    case netmc::dds::CONTROL_BEGIN_ITERATION:
      if (!control.job_spec().empty()) {
        // A job started without PREPARE_ITERATION: a simulated drive restarts where it begins; a
        // hardware drive must be brought to the start first.
        if (hardware(axis)) {
          link_.release(control.axis(), control.server(), control.job_id());
          link_.refuse(control, netmc::dds::AXIS_FAULT,
                       "axis " + control.axis() + " has a hardware drive: its server must move it to the start first "
                       "(PREPARE_ITERATION)");
          return;
        }
        if (!start_job(axis, control)) return;
      }
      begin(axis, control);
      return;
    case netmc::dds::CONTROL_END_ITERATION: {
      if (!axis.endpoint || axis.job_id != control.job_id() || axis.iteration != control.iteration() ||
          axis.phase != Phase::running) {
        return;
      }
      // Sampling stops now; the report waits two periods (at least 10 ms), since the last
      // setpoints travel best-effort on another topic and may arrive after this message: they
      // are counted as received, not as missing.
      axis.report_due = true;
      axis.commands_sent = control.cycle();
      const auto grace = std::max(std::chrono::duration<double>(2.0 * axis.sample_period_s),
                                  std::chrono::duration<double>(0.010));
      axis.report_at = Clock::now() + std::chrono::duration_cast<Clock::duration>(grace);
      axis.endpoint->supervised().end_iteration();
      axis.phase = Phase::ready;
      if (hardware(axis) && !link_.faulted(owned->first)) {
        // Back to the start at once: the next iteration begins there.
        axis.phase = Phase::preparing;
        axis.move.reset();
        axis.settled_reads = 0;
        axis.positioning_deadline = Clock::now() + link_.config().positioning.timeout;
        axis.next_poll = Clock::now();
      }
      return;
    }
    case netmc::dds::CONTROL_END_JOB:
      end_job(owned->first, axis, control);
      return;
    case netmc::dds::CONTROL_FAULT_RESET:
    case netmc::dds::CONTROL_ENABLE:
    case netmc::dds::CONTROL_DISABLE:
    case netmc::dds::CONTROL_QUICK_STOP:
    case netmc::dds::CONTROL_MOVE:
    case netmc::dds::CONTROL_JOG:
      return;
  }
}

void RealtimeAxisNode::commission(const std::string& axis_name, OwnedAxis& axis,
                                  const netmc::dds::JobControl& control) {
  const auto kind = control.kind();
  const bool motion = kind == netmc::dds::CONTROL_ENABLE || kind == netmc::dds::CONTROL_MOVE ||
                      kind == netmc::dds::CONTROL_JOG;
  std::string refusal;
  if (kind == netmc::dds::CONTROL_QUICK_STOP && axis.endpoint) {
    const bool own_job = control.server() == axis.server && control.job_id() == axis.job_id;
    quick_stop_job(axis_name, axis,
                   own_job ? "quick stop by its job's server (a limit the job crossed)"
                           : "quick stop by the operator (netmc quick-stop)");
  } else if (!axis.commissioning) {
    refusal = "axis " + axis_name + " has a simulated drive (" + link_.config().drives.at(axis_name).spec.describe() +
              "): it moves only in a job's time; commissioning needs a hardware drive (modbus-tcp, plugin)";
  } else if (axis.endpoint) {
    refusal = "axis " + axis_name + " runs job " + std::to_string(axis.job_id) + " of server " + axis.server +
              ": cancel it first (netmc cancel " + std::to_string(axis.job_id) + ")";
  } else if (motion && link_.faulted(axis_name)) {
    refusal = "axis " + axis_name + " is in fault: netmc reset " + link_.config().node + " first";
  } else {
    const double now = link_.now_s();
    try {
      if (axis.phase == Phase::stopping && kind != netmc::dds::CONTROL_QUICK_STOP) {
        refusal = "axis " + axis_name + " is coming to rest after its job: ask again once it is off";
      } else if (kind == netmc::dds::CONTROL_ENABLE) {
        refusal = axis.commissioning->enable(now);
      } else if (kind == netmc::dds::CONTROL_DISABLE) {
        axis.commissioning->disable(*axis.drive, now);
      } else if (kind == netmc::dds::CONTROL_QUICK_STOP) {
        axis.commissioning->quick_stop(*axis.drive);
        axis.phase = Phase::idle;
        axis.move.reset();
      } else if (kind == netmc::dds::CONTROL_MOVE) {
        refusal = axis.commissioning->move(control.start_position_m(), control.speed_m_s(), now);
      } else {
        refusal = axis.commissioning->jog(control.speed_m_s(), now);
      }
    } catch (const drive::DriveError& error) {
      refusal = error.what();
      axis.commissioning->release();
    }
  }
  const bool renewal = kind == netmc::dds::CONTROL_JOG && refusal.empty() && axis.command_refusal.empty() &&
                       axis.commissioning && axis.commissioning->motion() == CommissioningAxis::Motion::jogging;
  axis.command_number = control.job_id();
  axis.command_refusal = refusal;
  if (!refusal.empty()) {
    spdlog::warn("axis {}: commissioning command of server {} refused: {}", axis_name, control.server(), refusal);
  } else if (!renewal) {
    spdlog::info("axis {}: {} by server {}", axis_name, control_kind_name(kind), control.server());
  }
  axis.next_poll = Clock::now();
  report_drive(axis_name, axis);
  publish_status();  // at once: the operator waits on the command number
}

void RealtimeAxisNode::quick_stop_job(const std::string& axis_name, OwnedAxis& axis, const std::string& why) {
  // The operator's quick stop ends the job on this axis, as the watchdog's does.
  axis.endpoint->hold();
  axis.holding = true;
  try {
    if (hardware(axis)) axis.drive->write_controlword(drive::controlword::quick_stop);
  } catch (const drive::DriveError& error) {
    spdlog::error("axis {}: quick stop not sent: {}", axis_name, error.what());
  }
  if (axis.phase == Phase::preparing || axis.phase == Phase::ready) axis.phase = Phase::idle;
  axis.move.reset();
  spdlog::warn("axis {} job {}: {}", axis_name, axis.job_id, why);
  publish_job_event(axis_name, axis, axis.iteration, netmc::dds::AXIS_FAULT, "axis " + axis_name + ": " + why);
}

void RealtimeAxisNode::publish_job_event(const std::string& axis_name, const OwnedAxis& axis, std::uint32_t iteration,
                                         netmc::dds::AxisEventKind kind, const std::string& detail) {
  netmc::dds::AxisEvent event;
  event.axis(axis_name);
  event.server(axis.server);
  event.job_id(axis.job_id);
  event.iteration(iteration);
  event.kind(kind);
  event.detail(detail.substr(0, 255));
  link_.publish_event(event);
}

bool RealtimeAxisNode::start_job(OwnedAxis& axis, const netmc::dds::JobControl& control) {
  if (axis.commissioning && axis.commissioning->moving()) {
    refuse_start(axis, control,
                 std::string("axis ") + control.axis() + " is " + motion_name(axis.commissioning->motion()) +
                     " under the operator's commissioning: wait for it, or netmc disable it");
    return false;
  }
  if (!link_.linked_to_server(control)) {
    starts_.wait(control, Clock::now());
    return false;
  }
  try {
    static_cast<JobAxis&>(axis) = link_.start_job(control);
  } catch (const std::exception& error) {
    refuse_start(axis, control, error.what());
    return false;
  }
  axis.server = control.server();
  axis.drive = axis.endpoint->supervised().shared_drive();
  axis.phase = Phase::idle;
  if (axis.commissioning) axis.commissioning->release();  // the job takes over an enabled axis
  return true;
}

void RealtimeAxisNode::refuse_start(OwnedAxis& axis, const netmc::dds::JobControl& control, const std::string& why) {
  // A job this node cannot run must not take the node down: say so and stay ready.
  axis.endpoint.reset();
  axis.phase = Phase::idle;
  link_.release(control.axis(), control.server(), control.job_id());
  link_.refuse(control, netmc::dds::AXIS_FAULT, why);
}

void RealtimeAxisNode::settle_starts() {
  if (starts_.empty()) return;
  const auto linked = [this](const netmc::dds::JobControl& begin) { return link_.linked_to_server(begin); };
  const auto settled = starts_.settle(linked, Clock::now());
  for (const auto& start : settled) {
    if (start.linked) {
      handle(start.begin);
    } else {
      refuse_start(axes_.at(start.begin.axis()), start.begin, link_.why_not_linked(start.begin));
    }
    for (const auto& control : start.held_back) handle(control);
  }
}

void RealtimeAxisNode::prepare(const std::string& axis_name, OwnedAxis& axis, const netmc::dds::JobControl& control) {
  if (!control.job_spec().empty() && !start_job(axis, control)) return;
  if (!axis.endpoint || axis.job_id != control.job_id() || !std::isfinite(control.start_position_m())) return;
  axis.start_position_m = control.start_position_m();
  axis.ready_for = control.iteration();
  if (!hardware(axis) || axis.phase == Phase::ready) {
    say_ready(axis_name, axis);
    return;
  }
  const auto& limits = link_.config().drives.at(axis_name).limits;
  if (!(axis.start_position_m >= limits.position_min_m && axis.start_position_m <= limits.position_max_m)) {
    fail_preparation(axis_name, axis,
                     fmt::format("the job starts at {:.6g} m, outside the axis's window [{:g}, {:g}] m",
                                 axis.start_position_m, limits.position_min_m, limits.position_max_m));
    return;
  }
  if (axis.phase != Phase::preparing) {
    axis.phase = Phase::preparing;
    axis.move.reset();
    axis.settled_reads = 0;
    axis.positioning_deadline = Clock::now() + link_.config().positioning.timeout;
  }
  axis.endpoint->supervised().allow_return_into_window(true);  // the start is inside it
  axis.next_poll = Clock::now();
}

void RealtimeAxisNode::say_ready(const std::string& axis_name, OwnedAxis& axis) {
  if (axis.ready_for == 0) return;
  publish_job_event(axis_name, axis, axis.ready_for, netmc::dds::AXIS_READY, "");
  axis.ready_for = 0;
}

void RealtimeAxisNode::fail_preparation(const std::string& axis_name, OwnedAxis& axis, const std::string& why) {
  spdlog::error("axis {}: {}", axis_name, why);
  publish_job_event(axis_name, axis, axis.ready_for, netmc::dds::AXIS_FAULT, "axis " + axis_name + ": " + why);
  axis.ready_for = 0;
  axis.phase = Phase::stopping;
  axis.move.reset();
}

void RealtimeAxisNode::start_move(OwnedAxis& axis, double target_m, double position_m, double velocity_m_s) {
  const auto& positioning = link_.config().positioning;
  axis.move.emplace(position_m, velocity_m_s, target_m, positioning.velocity_m_s, positioning.acceleration_m_s2);
  axis.move_start_s = link_.now_s();
  axis.settled_reads = 0;
}

// A hardware drive between samples: each phase's exchange with it.
void RealtimeAxisNode::poll(const std::string& axis_name, OwnedAxis& axis, Clock::time_point now) {
  const auto& positioning = link_.config().positioning;
  axis.next_poll = now + (axis.phase == Phase::preparing || axis.phase == Phase::stopping ? kMovePoll
                          : axis.phase == Phase::idle ? kIdlePoll : kHoldPoll);
  drive::DriveFeedback reading;
  try {
    if (axis.endpoint) {
      reading = axis.endpoint->supervised().poll(link_.now_s() - axis.start_time_s);
      if (axis.endpoint->fault()) {
        report_fault(axis_name, axis);
        if (axis.phase == Phase::preparing || axis.phase == Phase::ready) {
          fail_preparation(axis_name, axis, *axis.endpoint->fault());
        }
        axis.phase = Phase::idle;
        return;
      }
    } else if (axis.commissioning) {
      reading = axis.commissioning->poll(*axis.drive, link_.now_s());
      report_motion(axis_name, axis);
      if (axis.commissioning->active()) {
        axis.next_poll = now + (axis.commissioning->motion() == CommissioningAxis::Motion::holding ? kHoldPoll : kMovePoll);
      }
    } else {
      reading = axis.drive->read();
    }
    if (axis.poll_failed) {
      spdlog::info("axis {}: its drive answers again", axis_name);
      axis.poll_failed = false;
      axis.reported_state = drive::PowerState::not_ready_to_switch_on;  // the state it shows next is news
    }
    reset_drive(axis_name, axis);
  } catch (const drive::DriveError& error) {
    const bool first = !axis.poll_failed;
    if (first) spdlog::warn("axis {}: {}", axis_name, error.what());
    axis.poll_failed = true;
    if (axis.commissioning && axis.commissioning->active()) {
      axis.commissioning->release(std::string("the drive did not answer: ") + error.what());
    }
    link_.report_unreachable(axis_name, error.what());
    if (first) publish_status();  // at once: a server deciding on this axis must know
    if (axis.phase == Phase::preparing) fail_preparation(axis_name, axis, error.what());
    return;
  }
  const auto state = drive::decode_statusword(reading.statusword);
  if (!axis.endpoint) {
    drive::PowerState shown = state.value_or(drive::PowerState::not_ready_to_switch_on);
    if (link_.faulted(axis_name) && shown != drive::PowerState::fault) {
      shown = ramping(shown) ? drive::PowerState::fault_reaction_active : drive::PowerState::fault;
    }
    link_.report_drive(axis_name, shown, reading);
    if (shown != axis.reported_state) {
      axis.reported_state = shown;
      spdlog::info("axis {}: {}", axis_name, drive::power_state_name(shown));
      link_.publish_status(netmc::dds::NODE_IDLE, std::string("axis ") + axis_name + ": " +
                                                      drive::power_state_name(shown));
    }
    if (state && ramping(*state)) axis.next_poll = now + kHoldPoll;
  } else {
    report_drive(axis_name, axis);
  }
  try {
    switch (axis.phase) {
      case Phase::idle:
      case Phase::running:
        return;
      case Phase::preparing: {
        if (state == drive::PowerState::fault) {
          fail_preparation(axis_name, axis,
                           "the drive is in Fault (error " + drive::describe_error_code(reading.error_code) +
                               "): reset it with netmc reset " + link_.config().node);
          return;
        }
        if (now > axis.positioning_deadline) {
          fail_preparation(axis_name, axis,
                           fmt::format("not at rest at the start {:.6g} m within {} ms of positioning (at {:.6g} m, "
                                       "{:.3g} m/s, {})",
                                       axis.start_position_m, positioning.timeout.count(), reading.position_m,
                                       reading.velocity_m_s,
                                       state ? drive::power_state_name(*state) : "no CiA 402 state"));
          return;
        }
        if (state != drive::PowerState::operation_enabled) {
          axis.move.reset();
          if (!state) return;
          if (const auto word = drive::controlword_towards(*state, drive::PowerState::operation_enabled)) {
            axis.drive->write_controlword(*word);
          }
          return;
        }
        if (!axis.move) {
          axis.drive->write_mode(drive::OperationMode::csp);
          axis.drive->write_target(drive::OperationMode::csp, reading.position_m);
          start_move(axis, axis.start_position_m, reading.position_m, reading.velocity_m_s);
        }
        const double t = link_.now_s() - axis.move_start_s;
        axis.drive->write_target(drive::OperationMode::csp, axis.move->position_m(t));
        if (t < axis.move->duration_s()) return;
        const bool settled = std::abs(reading.position_m - axis.start_position_m) <= positioning.tolerance_m &&
                             std::abs(reading.velocity_m_s) <= positioning.settle_velocity_m_s;
        axis.settled_reads = settled ? axis.settled_reads + 1 : 0;
        if (axis.settled_reads >= kSettledReads) {
          axis.endpoint->supervised().allow_return_into_window(false);
          axis.phase = Phase::ready;
          axis.next_poll = now + kHoldPoll;
          say_ready(axis_name, axis);
        }
        return;
      }
      case Phase::ready:
        // Held at the start for a server that fell silent: stop holding once its lease is over.
        if (now - axis.last_contact > link_.config().hold_lease) {
          spdlog::warn("axis {}: its server fell silent while it held the start: switching it off", axis_name);
          axis.endpoint.reset();
          axis.phase = Phase::stopping;
          axis.move.reset();
        }
        return;
      case Phase::stopping: {
        if (state != drive::PowerState::operation_enabled) {
          axis.phase = Phase::idle;
          return;
        }
        if (!axis.move) {
          // To rest on the positioning deceleration, where a stop from this speed ends.
          const double a = positioning.acceleration_m_s2;
          const double v = reading.velocity_m_s;
          axis.drive->write_mode(drive::OperationMode::csp);
          start_move(axis, reading.position_m + v * std::abs(v) / (2.0 * a), reading.position_m, v);
        }
        const double t = link_.now_s() - axis.move_start_s;
        axis.drive->write_target(drive::OperationMode::csp, axis.move->position_m(t));
        if (t >= axis.move->duration_s() && std::abs(reading.velocity_m_s) <= 10.0 * positioning.settle_velocity_m_s) {
          axis.drive->write_controlword(drive::controlword::shutdown);
          axis.phase = Phase::idle;
          axis.move.reset();
          axis.next_poll = now;
        }
        return;
      }
    }
  } catch (const drive::DriveError& error) {
    spdlog::error("axis {}: {}", axis_name, error.what());
    if (axis.phase == Phase::preparing) fail_preparation(axis_name, axis, error.what());
    axis.phase = Phase::idle;
  }
}

void RealtimeAxisNode::begin(OwnedAxis& axis, const netmc::dds::JobControl& control) {
  if (!axis.endpoint || axis.job_id != control.job_id() || !std::isfinite(control.start_time_s()) ||
      !std::isfinite(control.start_position_m())) {
    return;
  }
  axis.endpoint->begin_iteration(control.iteration(), control.start_position_m());
  axis.start_position_m = control.start_position_m();
  axis.iteration = control.iteration();
  axis.start_time_s = control.start_time_s();
  axis.next_cycle = 0;
  axis.last_setpoint_s = 0.0;
  axis.holding = false;
  axis.phase = Phase::running;
  axis.report_due = false;
  axis.samples = 0;
  axis.commands_received = 0;
  axis.server_send_times.clear();
  axis.applied_since_sample.clear();
  axis.feedback_sent.assign(kFeedbackTimes, OwnedAxis::FeedbackTime{});
  axis.newest_timed = -1;
  axis.round_trips_s.clear();
  axis.wake_late_s.clear();
  axis.round_trips_s.reserve_for(axis.cycles);
  axis.wake_late_s.reserve_for(axis.cycles);
  schedule(axis);
}

void RealtimeAxisNode::end_job(const std::string& axis_name, OwnedAxis& axis, const netmc::dds::JobControl& control) {
  if (axis.job_id != control.job_id() || !axis.endpoint) return;
  const bool enabled = axis.endpoint->supervised().power_state() == drive::PowerState::operation_enabled;
  axis.endpoint.reset();
  axis.report_due = false;
  axis.holding = false;
  axis.ready_for = 0;
  axis.move.reset();
  axis.phase = Phase::idle;
  try {
    if (hardware(axis) && enabled) {
      axis.phase = Phase::stopping;  // to rest, then switched off (poll)
      axis.next_poll = Clock::now();
    } else if (axis.drive && enabled) {
      axis.drive->write_controlword(drive::controlword::shutdown);
    }
  } catch (const drive::DriveError& error) {
    spdlog::error("axis {}: {}", axis_name, error.what());
  }
  link_.release(control.axis(), control.server(), control.job_id());
  publish_status();  // at once: a server deciding on these axes must not see a stale hold
}

void RealtimeAxisNode::handle(const netmc::dds::Setpoint& setpoint) {
  const auto owned = axes_.find(setpoint.axis());
  if (owned == axes_.end()) return;
  OwnedAxis& axis = owned->second;
  if (!axis.endpoint || !(axis.phase == Phase::running || axis.report_due) || axis.job_id != setpoint.job_id() ||
      axis.iteration != setpoint.iteration() ||
      !link_.from_holder(setpoint.axis(), setpoint.server(), setpoint.job_id())) {
    return;
  }
  if (axis.phase != Phase::running || axis.report_due) {  // arrived after the iteration's end: late, not lost
    ++axis.commands_received;
    return;
  }
  // Nothing but a setpoint of this job's cycles is looked at; the actuator trips on a command it
  // must not take (non-finite, beyond its limit) when it applies it (reported with the sample).
  if (!std::isfinite(setpoint.send_time_s()) || setpoint.cycle() >= axis.cycles) return;
  const auto arrived = Clock::now();
  const auto cycle = static_cast<std::int64_t>(setpoint.cycle());
  const auto& sent = axis.feedback_sent[setpoint.cycle() % kFeedbackTimes];
  if (cycle > axis.newest_timed && sent.cycle == setpoint.cycle() && sent.sent != Clock::time_point{}) {
    axis.round_trips_s.add(std::chrono::duration<double>(arrived - sent.sent).count());
    axis.newest_timed = cycle;
  }
  // The setpoint leaves for the actuator now: netsim's downlink delay starts here.
  const double now = link_.now_s() - axis.start_time_s;
  submit_to(*axis.endpoint, now, setpoint);
  if (axis.server_send_times.size() >= kMaxSetpointsInFlight) axis.server_send_times.erase(axis.server_send_times.begin());
  axis.server_send_times[setpoint.cycle()] = setpoint.send_time_s();
  axis.last_setpoint_s = now;
  ++axis.commands_received;
  if (hardware(axis)) {
    // Hardware runs on its own time: the command is written as it arrives.
    for (const auto& a : axis.endpoint->apply_arrived(now)) {
      if (axis.applied_since_sample.size() < netmc::dds::kMaxApplied) axis.applied_since_sample.push_back(a);
    }
    if (axis.endpoint->fault()) report_fault(owned->first, axis);
  }
}

void RealtimeAxisNode::schedule(OwnedAxis& axis) const {
  const double t = static_cast<double>(axis.next_cycle) * axis.sample_period_s;
  axis.next_sample = dds::steady_time_at(link_.config().time_base, axis.start_time_s + t);
}

void RealtimeAxisNode::report_fault(const std::string& axis_name, OwnedAxis& axis) {
  link_.report_fault(axis_name, axis, axis.server, axis.iteration);
  // No one moves a simulated drive's time once its job has stopped: its reaction ends now.
  if (axis.endpoint && axis.endpoint->fault() && !hardware(axis)) axis.endpoint->supervised().finish_reaction();
  report_drive(axis_name, axis);
}

void RealtimeAxisNode::sample(const std::string& axis_name, OwnedAxis& axis, Clock::time_point now) {
  axis.wake_late_s.add(std::chrono::duration<double>(now - axis.next_sample).count());
  const std::uint64_t k = axis.next_cycle;
  const double t = static_cast<double>(k) * axis.sample_period_s;
  netmc::dds::Feedback feedback;
  feedback.axis(axis_name);
  feedback.server(axis.server);
  feedback.job_id(axis.job_id);
  feedback.iteration(axis.iteration);
  const auto add_applied = [&](const sim::AppliedSetpoint& a) {
    if (feedback.applied().size() >= netmc::dds::kMaxApplied) return;
    netmc::dds::AppliedSetpoint applied = applied_entry(a);
    const auto sent = axis.server_send_times.find(a.sequence);  // see server_send_times
    if (sent != axis.server_send_times.end()) applied.send_time_s(sent->second);
    feedback.applied().push_back(applied);
  };
  for (const auto& a : axis.applied_since_sample) add_applied(a);
  axis.applied_since_sample.clear();
  if (k > 0 || hardware(axis)) {
    for (const auto& a : axis.endpoint->advance_to(t)) add_applied(a);
  }
  // Setpoints older than the newest applied one can no longer act.
  if (!feedback.applied().empty()) {
    axis.server_send_times.erase(axis.server_send_times.begin(),
                                 axis.server_send_times.upper_bound(feedback.applied().back().cycle()));
  }
  // Watchdog: a running axis without setpoints quick-stops rather than keep the last command.
  if (k > 0 && !axis.holding && t - axis.last_setpoint_s > std::chrono::duration<double>(watchdog_).count()) {
    axis.endpoint->hold();
    axis.holding = true;
    const double silent_ms = (t - axis.last_setpoint_s) * 1e3;
    spdlog::warn("axis {} job {} iteration {}: no setpoint for {:.0f} ms at cycle {}: quick stop", axis_name,
                 axis.job_id, axis.iteration, silent_ms, k);
    // The iteration cannot go on with this axis stopped: the server ends the job (its other axes
    // stop as commanded) instead of running its loops on to a completion that means nothing, or
    // winding them up until a command trips an axis. Not latched: the next job may run.
    publish_job_event(axis_name, axis, axis.iteration, netmc::dds::AXIS_FAULT,
                      fmt::format("quick stop after {:.0f} ms without a setpoint, at cycle {} of iteration {} (the "
                                  "node's watchdog, netmc-axis --watchdog {} ms)",
                                  silent_ms, k, axis.iteration, watchdog_.count()));
  }
  if (axis.endpoint->fault()) report_fault(axis_name, axis);  // before the sample
  set_sample(feedback, k, t, axis.endpoint->sample());
  set_downlink_counters(feedback, *axis.endpoint);
  link_.publish(feedback);
  axis.feedback_sent[k % kFeedbackTimes] = OwnedAxis::FeedbackTime{k, Clock::now()};
  ++axis.samples;
  ++axis.next_cycle;
  if (axis.next_cycle < axis.cycles) schedule(axis);
  report_drive(axis_name, axis);
}

void RealtimeAxisNode::end_iteration(const std::string& axis_name, OwnedAxis& axis) {
  axis.report_due = false;
  if (!axis.endpoint) return;
  netmc::dds::AxisEvent event;
  event.axis(axis_name);
  event.server(axis.server);
  event.job_id(axis.job_id);
  event.iteration(axis.iteration);
  event.kind(netmc::dds::AXIS_ITERATION_ENDED);
  event.samples(axis.samples);
  set_downlink_counters(event, *axis.endpoint);
  event.missing_setpoints(axis.commands_sent > axis.commands_received ? axis.commands_sent - axis.commands_received
                                                                      : 0);
  link_.publish_event(event);
  // The node's own view of the loop's timing, for the operator and bench/realtime_sweep.sh.
  const double us = 1e6;
  const std::string exchanges = axis.drive ? axis.drive->take_exchange_statistics() : std::string();
  spdlog::info("axis {} job {} iteration {}: {} samples, sample wake-up late p50 {:.0f} us "
                   "p99 {:.0f} us; round trip feedback->setpoint p50 {:.0f} us p99 {:.0f} us max {:.0f} us ({} "
                   "setpoints){}{}",
                   axis_name, axis.job_id, axis.iteration, axis.samples,
                   axis.wake_late_s.percentile(0.50) * us, axis.wake_late_s.percentile(0.99) * us,
                   axis.round_trips_s.percentile(0.50) * us, axis.round_trips_s.percentile(0.99) * us,
                   axis.round_trips_s.max() * us, axis.round_trips_s.size(), exchanges.empty() ? "" : "; ", exchanges);
}

}  // namespace netmc::axis
