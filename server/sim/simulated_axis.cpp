#include "server/sim/simulated_axis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace netmc::sim {

SimulatedAxis::SimulatedAxis(std::unique_ptr<plant::AxisPlant> plant,
                             plant::PositionSensor sensor, double command_limit, AxisLimits limits)
    : plant_(std::move(plant)), sensor_(std::move(sensor)), command_limit_(command_limit), limits_(limits) {
  limits_.validate();
}

void SimulatedAxis::trip(const std::string& reason) {
  if (!fault_) fault_ = reason;
  input_ = 0.0;  // quick stop: the drive is told to stand still
}

void SimulatedAxis::check_state() {
  const double x = plant_->position();
  const double v = plant_->velocity();
  if (!(x >= limits_.position_min_m && x <= limits_.position_max_m)) {
    trip(fmt::format("position {:.6g} m outside the window [{:g}, {:g}] m", x, limits_.position_min_m,
                     limits_.position_max_m));
  } else if (!(std::abs(v) <= limits_.velocity_m_s)) {
    trip(fmt::format("velocity {:.6g} m/s beyond the limit {:g} m/s", v, limits_.velocity_m_s));
  }
}

void SimulatedAxis::reset(double position) {
  plant_->reset(position, 0.0);
  // The sensor's noise stream runs on across iterations: noise does not repeat, so ILC cannot
  // learn it.
  freshness_.reset();
  input_ = 0.0;  // u(-1) = 0
  time_s_ = 0.0;
  input_changed_s_ = 0.0;
}

double SimulatedAxis::measure() { return sensor_.measure(plant_->position()); }

void SimulatedAxis::advance_to(double end_time_s, const std::vector<Delivery>& deliveries) {
  for (const Delivery& delivery : deliveries) {
    const double switch_time = std::clamp(delivery.arrival_time_s, time_s_, end_time_s);
    plant_->advance(switch_time - time_s_, input_);
    time_s_ = switch_time;
    if (!fault_) check_state();
    if (!freshness_.accept(delivery.sequence) || fault_) continue;
    // Limits are enforced here, at the axis, whatever the server sent: the operator's trip,
    // then the drive's saturation and slew rate.
    if (!std::isfinite(delivery.payload)) {
      trip(fmt::format("command {:g} (cycle {}) not finite", delivery.payload, delivery.sequence));
      continue;
    }
    if (!(std::abs(delivery.payload) <= limits_.command)) {
      trip(fmt::format("command {:g} (cycle {}) beyond the axis's limit {:g}", delivery.payload, delivery.sequence,
                       limits_.command));
      continue;
    }
    double command = std::clamp(delivery.payload, -command_limit_, command_limit_);
    if (std::isfinite(limits_.slew_per_s)) {
      const double step = limits_.slew_per_s * (time_s_ - input_changed_s_);
      command = std::clamp(command, input_ - step, input_ + step);
    }
    if (command != input_) input_changed_s_ = time_s_;
    input_ = command;
  }
  plant_->advance(end_time_s - time_s_, input_);
  time_s_ = end_time_s;
  if (!fault_) check_state();
}

}  // namespace netmc::sim
