#include "server/drive/emulated_drive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace netmc::drive {
namespace {

constexpr double kPi = 3.14159265358979323846;

void require_positive_finite(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("drive: ") + name + " must be a positive finite number");
  }
}

// Acceleration per input unit from rest: the mean of the responses to +-amplitude over a short
// step (friction and any dead zone are symmetric enough for a loop gain).
double probe_input_gain(const plant::AxisPlant& plant, double amplitude) {
  constexpr double kProbeS = 0.002;
  double velocity[2];
  for (int sign = 0; sign < 2; ++sign) {
    auto probe = plant.clone();
    probe->reset(0.0, 0.0);
    probe->advance(kProbeS, sign == 0 ? amplitude : -amplitude);
    velocity[sign] = probe->velocity();
  }
  return (velocity[0] - velocity[1]) / (2.0 * amplitude * kProbeS);
}

}  // namespace

void EmulatedDriveSettings::validate() const {
  if (!(max_input > 0.0)) throw std::invalid_argument("drive: max_input must be a positive number");
  require_positive_finite(quick_stop_deceleration_m_s2, "quick_stop_deceleration");
  require_positive_finite(cycle_s, "cycle");
  require_positive_finite(velocity_loop_hz, "velocity_loop_hz");
  require_positive_finite(standstill_velocity_m_s, "standstill_velocity");
  require_positive_finite(position_window_m, "position_window");
}

EmulatedDrive::EmulatedDrive(std::unique_ptr<plant::AxisPlant> plant, EmulatedDriveSettings settings)
    : plant_(std::move(plant)), settings_(settings) {
  settings_.validate();
  input_gain_ = probe_input_gain(*plant_, std::min(10.0, settings_.max_input));
  if (!(input_gain_ > 0.0) || !std::isfinite(input_gain_)) {
    throw std::invalid_argument("drive: the plant does not accelerate with its input (" + plant_->describe() +
                                "): its loops cannot be tuned");
  }
}

void EmulatedDrive::restart_at(double position_m) {
  plant_->reset(position_m, 0.0);
  time_ = 0.0;
  next_cycle_ = 0.0;
  input_ = 0.0;
  target_position_m_ = position_m;
  target_velocity_m_s_ = 0.0;
  target_torque_ = 0.0;
  feedforward_velocity_m_s_ = 0.0;
  last_target_time_ = -std::numeric_limits<double>::infinity();
  target_interval_s_ = 0.0;
  velocity_integral_ = 0.0;
}

bool EmulatedDrive::loops_active() const {
  const PowerState state = machine_.state();
  if (state == PowerState::quick_stop_active || state == PowerState::fault_reaction_active) return true;
  return state == PowerState::operation_enabled && mode_ != OperationMode::cst;
}

double EmulatedDrive::clamp_input(double input) const {
  return std::clamp(input, -settings_.max_input, settings_.max_input);
}

void EmulatedDrive::advance_to(double time_s) {
  if (!(time_s >= time_)) return;
  while (true) {
    if (!loops_active()) {
      // The torque target held (CST), or no power: the plant as the studies run it. (Its state
      // is checked where it is read: SimulatedDrive::read, the emulator's registers.)
      input_ = machine_.state() == PowerState::operation_enabled ? clamp_input(target_torque_) : 0.0;
      plant_->advance(time_s - time_, input_);
      time_ = time_s;
      next_cycle_ = std::max(next_cycle_, time_);
      return;
    }
    if (time_ >= next_cycle_) {
      run_loops();
      next_cycle_ += settings_.cycle_s;
      if (!loops_active()) continue;  // a ramp ended: the rest without loops
    }
    const double step_end = std::min(time_s, next_cycle_);
    plant_->advance(step_end - time_, input_);
    time_ = step_end;
    if (time_ >= time_s) break;
  }
  check_model();
}

void EmulatedDrive::check_model() {
  if (!std::isfinite(plant_->position()) || !std::isfinite(plant_->velocity())) {
    raise_fault(error_code::plant_not_finite);
  }
}

double EmulatedDrive::velocity_loop(double velocity_reference, double acceleration_feedforward) {
  const double omega = 2.0 * kPi * settings_.velocity_loop_hz;
  const double gain = omega / input_gain_;  // input per m/s
  const double error = velocity_reference - plant_->velocity();
  const double unclamped = velocity_integral_ + gain * error + acceleration_feedforward / input_gain_;
  const double output = clamp_input(unclamped);
  // Integrate only while the stage is not saturated (no wind-up); corner at omega / 4.
  if (output == unclamped) velocity_integral_ += gain * (omega / 4.0) * error * settings_.cycle_s;
  return output;
}

void EmulatedDrive::run_loops() {
  const PowerState state = machine_.state();
  if (state == PowerState::quick_stop_active || state == PowerState::fault_reaction_active) {
    // The velocity reference runs from where the ramp began to zero at the quick stop deceleration.
    const double a = settings_.quick_stop_deceleration_m_s2;
    const double elapsed = time_ - ramp_start_time_;
    const double speed = std::max(0.0, std::abs(ramp_start_velocity_) - a * elapsed);
    const double sign = ramp_start_velocity_ < 0.0 ? -1.0 : 1.0;
    const bool ramp_done = speed == 0.0;
    input_ = velocity_loop(sign * speed, ramp_done ? 0.0 : -sign * a);
    // At standstill, or a second past the ramp's end at the latest (a drive's quick stop timeout).
    const double ramp_s = std::abs(ramp_start_velocity_) / a;
    if ((ramp_done && std::abs(plant_->velocity()) < settings_.standstill_velocity_m_s) || elapsed > ramp_s + 1.0) {
      machine_.reaction_complete();
      input_ = 0.0;
    }
    return;
  }
  if (mode_ == OperationMode::csv) {
    input_ = velocity_loop(target_velocity_m_s_, 0.0);
    return;
  }
  // CSP: position loop at a quarter of the velocity loop's bandwidth. The feed-forward lasts
  // until the master's next target is overdue.
  if (time_ - last_target_time_ > 2.0 * target_interval_s_) feedforward_velocity_m_s_ = 0.0;
  const double omega = 2.0 * kPi * settings_.velocity_loop_hz;
  const double reference = feedforward_velocity_m_s_ + omega / 4.0 * (target_position_m_ - plant_->position());
  input_ = velocity_loop(reference, 0.0);
}

void EmulatedDrive::start_ramp() {
  ramp_start_time_ = time_;
  ramp_start_velocity_ = plant_->velocity();
  velocity_integral_ = 0.0;
  next_cycle_ = time_;  // the ramp's loop acts at once
}

void EmulatedDrive::apply_controlword(std::uint16_t word) {
  const PowerState before = machine_.state();
  machine_.apply(word);
  const PowerState after = machine_.state();
  if (after == before) return;
  if (after == PowerState::quick_stop_active) start_ramp();
  if (after == PowerState::operation_enabled) {
    // A drive enables where it stands: no jump to a stale target.
    target_position_m_ = plant_->position();
    target_velocity_m_s_ = 0.0;
    target_torque_ = 0.0;
    feedforward_velocity_m_s_ = 0.0;
    velocity_integral_ = 0.0;
    next_cycle_ = time_;
  }
}

void EmulatedDrive::set_mode(OperationMode mode) {
  if (mode == mode_) return;
  mode_ = mode;
  velocity_integral_ = 0.0;
  feedforward_velocity_m_s_ = 0.0;
  // A new mode starts from where the axis is: no jump to a target written for another mode, and
  // its first target is a position, not a motion.
  target_position_m_ = plant_->position();
  target_velocity_m_s_ = 0.0;
  last_target_time_ = -std::numeric_limits<double>::infinity();
  next_cycle_ = time_;
}

void EmulatedDrive::set_target(OperationMode mode, double value) {
  switch (mode) {
    case OperationMode::csp: {
      // The targets' own velocity: cyclic targets move by it every cycle of the master. A target
      // after a pause (more than 50 ms) is a new position, not a motion.
      const double interval = time_ - last_target_time_;
      feedforward_velocity_m_s_ = interval > 0.0 && interval <= 0.05 ? (value - target_position_m_) / interval : 0.0;
      target_interval_s_ = interval;
      last_target_time_ = time_;
      target_position_m_ = value;
      break;
    }
    case OperationMode::csv: target_velocity_m_s_ = value; break;
    case OperationMode::cst: target_torque_ = value; break;
  }
  // CST acts from now: the input switch of paper 001, eq. 4, inside the period.
  if (mode == OperationMode::cst && mode_ == OperationMode::cst && machine_.state() == PowerState::operation_enabled) {
    input_ = clamp_input(target_torque_);
  }
}

void EmulatedDrive::set_quick_stop_deceleration(double deceleration_m_s2) {
  if (!(deceleration_m_s2 > 0.0) || !std::isfinite(deceleration_m_s2)) return;
  settings_.quick_stop_deceleration_m_s2 = deceleration_m_s2;
}

void EmulatedDrive::raise_fault(std::uint16_t code) {
  const PowerState before = machine_.state();
  machine_.fault(code);
  if (machine_.state() == PowerState::fault_reaction_active && before != PowerState::fault_reaction_active) {
    start_ramp();
  }
}

std::uint16_t EmulatedDrive::statusword() const {
  std::uint16_t word = machine_.statusword();
  if (machine_.state() == PowerState::operation_enabled) {
    const bool reached = mode_ == OperationMode::csp
                             ? std::abs(plant_->position() - target_position_m_) <= settings_.position_window_m
                         : mode_ == OperationMode::csv
                             ? std::abs(plant_->velocity() - target_velocity_m_s_) <= settings_.standstill_velocity_m_s
                             : true;
    if (reached) word |= statusword::target_reached;
    if (std::isfinite(settings_.max_input) && std::abs(input_) >= settings_.max_input) {
      word |= statusword::internal_limit_active;
    }
  }
  return word;
}

}  // namespace netmc::drive
