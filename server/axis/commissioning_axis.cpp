#include "server/axis/commissioning_axis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace netmc::axis {
namespace {

bool enabled(CommissioningAxis::Motion motion) {
  using M = CommissioningAxis::Motion;
  return motion == M::holding || motion == M::moving || motion == M::jogging;
}

std::string not_enabled(CommissioningAxis::Motion motion) {
  using M = CommissioningAxis::Motion;
  if (motion == M::enabling) return "the axis is still being enabled";
  if (motion == M::stopping) return "the axis is being switched off";
  return "the axis is not enabled (netmc enable NODE AXIS first)";
}

}  // namespace

const char* motion_name(CommissioningAxis::Motion motion) {
  switch (motion) {
    case CommissioningAxis::Motion::off: return "off";
    case CommissioningAxis::Motion::enabling: return "enabling";
    case CommissioningAxis::Motion::holding: return "holding";
    case CommissioningAxis::Motion::moving: return "moving";
    case CommissioningAxis::Motion::jogging: return "jogging";
    case CommissioningAxis::Motion::stopping: return "stopping";
  }
  return "off";
}

CommissioningAxis::CommissioningAxis(CommissioningSettings settings, drive::AxisLimits limits)
    : settings_(settings), limits_(limits) {}

std::string CommissioningAxis::enable(double now_s) {
  if (enabled(motion_) || motion_ == Motion::enabling) return "";
  if (motion_ == Motion::stopping) return "the axis is being switched off: enable it once it is off";
  motion_ = Motion::enabling;
  note_.clear();
  enable_until_s_ = now_s + settings_.enable_timeout_s;
  mode_written_ = false;
  profile_.reset();
  following_error_m_ = 0.0;
  return "";
}

std::string CommissioningAxis::move(double target_m, double speed_m_s, double now_s) {
  if (!enabled(motion_)) return not_enabled(motion_);
  if (!std::isfinite(target_m)) return "the target must be a finite position in m";
  if (!(target_m >= limits_.position_min_m && target_m <= limits_.position_max_m)) {
    return fmt::format("the target {:.6g} m is outside the axis's window [{:g}, {:g}] m", target_m,
                       limits_.position_min_m, limits_.position_max_m);
  }
  if (speed_m_s == 0.0) speed_m_s = std::min(settings_.velocity_m_s, limits_.velocity_m_s);
  if (!(speed_m_s > 0.0 && std::isfinite(speed_m_s))) return "the speed must be a positive number of m/s";
  if (speed_m_s > limits_.velocity_m_s) {
    return fmt::format("the speed {:g} m/s is beyond the axis's velocity limit {:g} m/s", speed_m_s,
                       limits_.velocity_m_s);
  }
  note_.clear();
  plan(target_m, speed_m_s, now_s);
  motion_ = Motion::moving;
  return "";
}

std::string CommissioningAxis::jog(double speed_m_s, double now_s) {
  if (speed_m_s == 0.0) {
    if (motion_ == Motion::jogging) {
      plan_stop(now_s);
      motion_ = Motion::moving;
    }
    return "";
  }
  if (!enabled(motion_)) return not_enabled(motion_);
  if (!std::isfinite(speed_m_s)) return "the jog speed must be a finite number of m/s";
  if (std::abs(speed_m_s) > limits_.velocity_m_s) {
    return fmt::format("the jog speed {:g} m/s is beyond the axis's velocity limit {:g} m/s", std::abs(speed_m_s),
                       limits_.velocity_m_s);
  }
  if (!std::isfinite(limits_.position_min_m) || !std::isfinite(limits_.position_max_m)) {
    return "the axis has no position window to jog within (netmc-axis --position-window)";
  }
  if (motion_ == Motion::jogging && speed_m_s == jog_speed_m_s_) {
    jog_until_s_ = now_s + settings_.jog_deadman_s;  // the same jog, renewed
    return "";
  }
  // Towards the window's edge, where the ramp brings it to rest just inside.
  const double margin = 1e-3 * (limits_.position_max_m - limits_.position_min_m);
  const double edge = speed_m_s > 0.0 ? limits_.position_max_m - margin : limits_.position_min_m + margin;
  const double at = commanded(now_s).first;
  if ((speed_m_s > 0.0 && at >= edge - 1e-9) || (speed_m_s < 0.0 && at <= edge + 1e-9)) {
    return fmt::format("the axis is at the window's {} edge ({:.6g} m)", speed_m_s > 0.0 ? "upper" : "lower", at);
  }
  note_.clear();
  plan(edge, std::abs(speed_m_s), now_s);
  motion_ = Motion::jogging;
  jog_speed_m_s_ = speed_m_s;
  jog_until_s_ = now_s + settings_.jog_deadman_s;
  return "";
}

void CommissioningAxis::disable(drive::Drive& drive, double now_s) {
  if (enabled(motion_)) {
    plan_stop(now_s);
    motion_ = Motion::stopping;
    return;
  }
  if (motion_ == Motion::stopping) return;
  // Off or only being enabled: nothing moves, the power stage goes off now.
  motion_ = Motion::off;
  profile_.reset();
  drive.write_controlword(drive::controlword::shutdown);
}

void CommissioningAxis::quick_stop(drive::Drive& drive) {
  release("quick stop by the operator");
  drive.write_controlword(drive::controlword::quick_stop);
}

void CommissioningAxis::release(const std::string& note) {
  motion_ = Motion::off;
  profile_.reset();
  following_error_m_ = 0.0;
  note_ = note;
}

std::pair<double, double> CommissioningAxis::commanded(double now_s) const {
  if (!profile_) return {hold_m_, 0.0};
  const double t = now_s - profile_start_s_;
  return {profile_->position_m(t), profile_->velocity_m_s(t)};
}

void CommissioningAxis::plan_stop(double now_s) {
  const auto [p, v] = commanded(now_s);
  const double stop = std::clamp(p + v * std::abs(v) / (2.0 * settings_.acceleration_m_s2), limits_.position_min_m,
                                 limits_.position_max_m);
  plan(stop, std::max(std::abs(v), settings_.velocity_m_s), now_s);
}

void CommissioningAxis::plan(double target_m, double speed_m_s, double now_s) {
  // From the profile (or the hold) of an enabled axis; an axis just enabled holds where it was read.
  const auto [p, v] = profile_ || enabled(motion_) ? commanded(now_s) : std::pair{last_position_m_, 0.0};
  profile_.emplace(p, v, target_m, speed_m_s, settings_.acceleration_m_s2);
  profile_start_s_ = now_s;
  hold_m_ = target_m;
}

drive::DriveFeedback CommissioningAxis::poll(drive::Drive& drive, double now_s) {
  const drive::DriveFeedback feedback = drive.read();
  last_position_m_ = feedback.position_m;
  if (motion_ == Motion::off) return feedback;
  const auto state = drive::decode_statusword(feedback.statusword);
  const std::string state_text = state ? drive::power_state_name(*state) : "no CiA 402 state";
  if (motion_ == Motion::enabling) {
    if (state == drive::PowerState::fault) {
      release("enable failed: the drive is in Fault (error " + drive::describe_error_code(feedback.error_code) +
          "): netmc reset NODE first");
      return feedback;
    }
    if (state == drive::PowerState::operation_enabled) {
      hold_m_ = feedback.position_m;
      motion_ = Motion::holding;
      return feedback;
    }
    if (now_s > enable_until_s_) {
      release(fmt::format("enable failed: the drive stayed in {} for {:g} s", state_text, settings_.enable_timeout_s));
      return feedback;
    }
    if (!state) return feedback;
    // CSP, targeting where the axis stands, before the power stage comes on: it holds there.
    if (!mode_written_) {
      drive.write_mode(drive::OperationMode::csp);
      mode_written_ = true;
    }
    drive.write_target(drive::OperationMode::csp, feedback.position_m);
    if (const auto word = drive::controlword_towards(*state, drive::PowerState::operation_enabled)) {
      drive.write_controlword(*word);
    }
    return feedback;
  }
  if (state != drive::PowerState::operation_enabled) {
    release("the drive left Operation enabled: " + state_text +
        (state == drive::PowerState::fault ? " (error " + drive::describe_error_code(feedback.error_code) + ")" : ""));
    return feedback;
  }
  if (motion_ == Motion::jogging && now_s > jog_until_s_) {
    jog(0.0, now_s);
    note_ = fmt::format("jog stopped: no jog command for {:g} s (the deadman)", settings_.jog_deadman_s);
  }
  double commanded = hold_m_;
  if (profile_) {
    const double t = now_s - profile_start_s_;
    commanded = profile_->position_m(t);
    if (t >= profile_->duration_s()) {
      profile_.reset();
      commanded = hold_m_;
      if (motion_ == Motion::stopping) {
        drive.write_target(drive::OperationMode::csp, commanded);
        drive.write_controlword(drive::controlword::shutdown);
        release();
        return feedback;
      }
      if (motion_ == Motion::jogging) note_ = "jog ended at the window's edge";
      motion_ = Motion::holding;
    }
  }
  following_error_m_ = commanded - feedback.position_m;
  if (std::abs(following_error_m_) > settings_.following_error_limit_m) {
    const double error = following_error_m_;
    drive.write_controlword(drive::controlword::quick_stop);
    release(fmt::format("following error {:.3f} mm beyond the limit {:.3f} mm (commanded {:.6f} m, actual {:.6f} m): "
                    "quick stop",
                    error * 1e3, settings_.following_error_limit_m * 1e3, commanded, feedback.position_m));
    following_error_m_ = error;
    return feedback;
  }
  drive.write_target(drive::OperationMode::csp, commanded);
  return feedback;
}

}  // namespace netmc::axis
