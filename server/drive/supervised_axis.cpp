#include "server/drive/supervised_axis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace netmc::drive {

SupervisedAxis::SupervisedAxis(std::shared_ptr<Drive> drive, double command_limit, AxisLimits limits)
    : drive_(std::move(drive)),
      mode_(drive_->job_mode()),
      command_limit_(command_limit),
      limits_(limits),
      supervision_(limits.following_error_m, limits.velocity_m_s, !drive_->virtual_time()) {
  limits_.validate();
}

SupervisedAxis::~SupervisedAxis() {
  if (drive_) set_cycle_budget(0.0);
}

void SupervisedAxis::follow_reference(std::function<double(double)> reference_m, double sample_period_s) {
  reference_m_ = std::move(reference_m);
  sample_period_s_ = sample_period_s;
}

void SupervisedAxis::set_cycle_budget(double budget_s) {
  if (drive_->virtual_time() || (budget_s == 0.0 && !budget_set_)) return;
  try {
    drive_->set_cycle_budget(budget_s);
    budget_set_ = budget_s > 0.0;
  } catch (const DriveError& error) {
    trip(error.what());
  }
}

void SupervisedAxis::end_iteration() {
  running_ = false;
  set_cycle_budget(0.0);
}

void SupervisedAxis::check_feedback(double time_s, std::chrono::steady_clock::time_point read_start) {
  if (!reference_m_ || !running_ || fault_) return;
  SupervisedSample sample;
  sample.cycle = static_cast<std::uint64_t>(std::llround(time_s / sample_period_s_));
  sample.job_time_s = time_s;
  // A drive on its own time was read just now: a jump is judged over the time that really passed.
  const auto since_epoch = [this](std::chrono::steady_clock::time_point at) {
    return std::chrono::duration<double>(at - epoch_).count();
  };
  sample.time_s = drive_->virtual_time() ? time_s : since_epoch(std::chrono::steady_clock::now());
  sample.read_start_s = drive_->virtual_time() ? time_s : since_epoch(read_start);
  sample.reference_m = reference_m_(time_s);
  sample.position_m = reading_.position_m;
  sample.velocity_m_s = reading_.velocity_m_s;
  if (const auto reason = supervision_.check(sample)) trip(*reason);
}

void SupervisedAxis::trip(const std::string& reason) {
  if (!fault_) fault_ = reason;
  if (!running_) return;
  running_ = false;
  try {
    drive_->write_controlword(controlword::quick_stop);
  } catch (const DriveError& error) {
    *fault_ += fmt::format("; quick stop not confirmed: {}", error.what());
  }
}

void SupervisedAxis::quick_stop() {
  if (!running_) return;
  running_ = false;
  try {
    drive_->write_controlword(controlword::quick_stop);
  } catch (const DriveError& error) {
    trip(fmt::format("quick stop not sent: {}", error.what()));
    return;
  }
  refresh();  // the state it is in now
}

void SupervisedAxis::check_state() {
  const double x = reading_.position_m;
  const double v = reading_.velocity_m_s;
  const bool returning = return_allowed_ && ((x < limits_.position_min_m && v >= 0.0) ||
                                              (x > limits_.position_max_m && v <= 0.0));
  if (!(x >= limits_.position_min_m && x <= limits_.position_max_m) && !returning) {
    trip(fmt::format("position {:.6g} m outside the window [{:g}, {:g}] m", x, limits_.position_min_m,
                     limits_.position_max_m));
  } else if (!(std::abs(v) <= limits_.velocity_m_s)) {
    trip(fmt::format("velocity {:.6g} m/s beyond the limit {:g} m/s", v, limits_.velocity_m_s));
  } else if (running_) {
    const auto state = decode_statusword(reading_.statusword);
    if (state != PowerState::operation_enabled) {
      trip(fmt::format("the drive left Operation enabled: {} (statusword 0x{:04X}), error {}",
                       state ? power_state_name(*state) : "no CiA 402 state", reading_.statusword,
                       describe_error_code(reading_.error_code)));
    }
  }
}

void SupervisedAxis::refresh() {
  try {
    reading_ = drive_->read();
  } catch (const DriveError& error) {
    trip(error.what());
    return;
  }
  if (!reading_.has_velocity) {
    // Differentiated where the drive reports no velocity.
    reading_.velocity_m_s = previous_position_m_ && reading_time_s_ > previous_time_s_
                                ? (reading_.position_m - *previous_position_m_) / (reading_time_s_ - previous_time_s_)
                                : 0.0;
    previous_position_m_ = reading_.position_m;
    previous_time_s_ = reading_time_s_;
  }
  if (!fault_) check_state();
}

void SupervisedAxis::enable_now() {
  // Each step is one transition of the virtual drive, which takes it at once.
  for (int step = 0; step < 8; ++step) {
    const auto state = decode_statusword(drive_->read().statusword);
    if (!state || *state == PowerState::operation_enabled) return;
    const auto word = controlword_towards(*state, PowerState::operation_enabled);
    if (!word) return;
    drive_->write_controlword(*word);
  }
}

void SupervisedAxis::begin_iteration(double position_m) {
  freshness_.reset();
  input_ = 0.0;  // u(-1) = 0
  time_s_ = 0.0;
  input_changed_s_ = 0.0;
  reading_time_s_ = 0.0;
  previous_position_m_.reset();
  if (drive_->virtual_time()) {
    drive_->restart_at(position_m);
    if (!fault_) {
      enable_now();
      drive_->write_mode(mode_);
    }
    job_mode_pending_ = false;
  } else {
    job_mode_pending_ = !fault_;
  }
  refresh();
  const auto state = decode_statusword(reading_.statusword);
  running_ = !fault_ && state == PowerState::operation_enabled;
  supervision_.begin();
  if (running_ && reference_m_) set_cycle_budget(std::max(sample_period_s_, kMinCycleBudgetS));
  if (!fault_ && !running_) {
    trip(fmt::format("the drive is not in Operation enabled at the start of the iteration: {} (error {})",
                     state ? power_state_name(*state) : "no CiA 402 state", describe_error_code(reading_.error_code)));
  }
}

bool SupervisedAxis::accept_horizon(std::uint64_t cycle, const std::vector<double>& commands) {
  if (fault_) return false;
  for (std::size_t j = 0; j < commands.size(); ++j) {
    if (!std::isfinite(commands[j])) {
      trip(fmt::format("command {:g} (cycle {}, horizon entry {} of {}) not finite", commands[j], cycle, j,
                       commands.size()));
      return false;
    }
  }
  return true;
}

bool SupervisedAxis::accept_horizon_entry(std::uint64_t cycle, std::size_t entry, std::size_t entries, double command) {
  if (fault_) return false;
  if (!(std::abs(command) <= limits_.command)) {
    trip(fmt::format("command {:g} (cycle {}, horizon entry {} of {}) beyond the axis's limit {:g}", command, cycle,
                     entry, entries, limits_.command));
    return false;
  }
  return true;
}

void SupervisedAxis::apply_one(const Delivery& delivery) {
  if (!freshness_.accept(delivery.sequence) || fault_ || !running_) return;
  // Limits are enforced here, at the axis, whatever the server sent: the operator's trip,
  // then the job's saturation and the slew rate.
  if (!std::isfinite(delivery.payload)) {
    trip(fmt::format("command {:g} (cycle {}) not finite", delivery.payload, delivery.sequence));
    return;
  }
  if (!(std::abs(delivery.payload) <= limits_.command)) {
    trip(fmt::format("command {:g} (cycle {}) beyond the axis's limit {:g}", delivery.payload, delivery.sequence,
                     limits_.command));
    return;
  }
  double command = std::clamp(delivery.payload, -command_limit_, command_limit_);
  if (std::isfinite(limits_.slew_per_s)) {
    const double step = limits_.slew_per_s * (time_s_ - input_changed_s_);
    command = std::clamp(command, input_ - step, input_ + step);
  }
  if (command != input_) input_changed_s_ = time_s_;
  input_ = command;
  try {
    drive_->write_target(mode_, command);
  } catch (const DriveError& error) {
    trip(error.what());
  }
}

void SupervisedAxis::apply(const std::vector<Delivery>& deliveries, double until_s) {
  const bool virtual_time = drive_->virtual_time();
  // The travel and speed at each switch instant too, where there is a limit to check them
  // against (a simulation's input switches between samples; netmc sim's axes have no limits).
  const bool check_between = limits_.any();
  for (const Delivery& delivery : deliveries) {
    const double switch_time = std::clamp(delivery.arrival_time_s, time_s_, until_s);
    time_s_ = switch_time;
    if (virtual_time) {
      drive_->cycle(switch_time);
      reading_time_s_ = switch_time;
      if (check_between) refresh();
    }
    apply_one(delivery);
  }
}

const DriveFeedback& SupervisedAxis::sample(double time_s) {
  // The wall clock only for a supervised drive on its own time: not in the simulation's loop.
  const auto read_start = reference_m_ && !drive_->virtual_time() ? std::chrono::steady_clock::now()
                                                                  : std::chrono::steady_clock::time_point{};
  time_s_ = std::max(time_s_, time_s);
  reading_time_s_ = time_s_;
  try {
    if (job_mode_pending_) {
      // From here the job's commands act; until here the drive held its position.
      // Torque and velocity start at zero; a position target starts where the axis stands.
      job_mode_pending_ = false;
      drive_->write_target(mode_, mode_ == OperationMode::csp ? reading_.position_m : 0.0);
      drive_->write_mode(mode_);
    }
    drive_->cycle(time_s_);
  } catch (const DriveError& error) {
    trip(error.what());
  }
  refresh();
  check_feedback(time_s, read_start);
  return reading_;
}

void SupervisedAxis::advance_to(double end_time_s, const std::vector<Delivery>& deliveries) {
  apply(deliveries, end_time_s);
  sample(end_time_s);
}

void SupervisedAxis::finish_reaction() {
  if (!drive_->virtual_time()) return;
  // Ten seconds of virtual time at most: a ramp ends a second after its own length anyway.
  for (int step = 0; step < 1000; ++step) {
    const auto state = decode_statusword(drive_->read().statusword);
    if (state != PowerState::quick_stop_active && state != PowerState::fault_reaction_active) break;
    time_s_ += 0.01;
    drive_->cycle(time_s_);
  }
  reading_ = drive_->read();
}

const DriveFeedback& SupervisedAxis::poll(double time_s) {
  reading_time_s_ = time_s;
  refresh();
  return reading_;
}

void reset_drive_fault(Drive& drive) {
  if (decode_statusword(drive.read().statusword) == PowerState::fault) {
    drive.write_controlword(controlword::disable_voltage);
    drive.write_controlword(controlword::fault_reset);
  }
}

void SupervisedAxis::clear_fault() {
  fault_.reset();
  try {
    reset_drive_fault(*drive_);
    reading_ = drive_->read();
  } catch (const DriveError& error) {
    fault_ = fmt::format("fault reset failed: {}", error.what());
  }
}

PowerState SupervisedAxis::power_state() const {
  const auto state = decode_statusword(reading_.statusword).value_or(PowerState::not_ready_to_switch_on);
  if (!fault_) return state;
  const bool moving = state == PowerState::operation_enabled || state == PowerState::quick_stop_active ||
                      state == PowerState::fault_reaction_active;
  return moving ? PowerState::fault_reaction_active : PowerState::fault;
}

}  // namespace netmc::drive
