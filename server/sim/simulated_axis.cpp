#include "server/sim/simulated_axis.hpp"

#include <algorithm>

namespace netmc::sim {

SimulatedAxis::SimulatedAxis(std::unique_ptr<plant::AxisPlant> plant,
                             plant::PositionSensor sensor, double command_limit)
    : plant_(std::move(plant)), sensor_(std::move(sensor)), command_limit_(command_limit) {}

void SimulatedAxis::reset(double position) {
  plant_->reset(position, 0.0);
  // The sensor's noise stream runs on across iterations: noise does not repeat, so ILC cannot
  // learn it.
  freshness_.reset();
  input_ = 0.0;  // u(-1) = 0
  time_s_ = 0.0;
}

double SimulatedAxis::measure() { return sensor_.measure(plant_->position()); }

void SimulatedAxis::advance_to(double end_time_s, const std::vector<Delivery>& deliveries) {
  for (const Delivery& delivery : deliveries) {
    const double switch_time = std::clamp(delivery.arrival_time_s, time_s_, end_time_s);
    plant_->advance(switch_time - time_s_, input_);
    time_s_ = switch_time;
    if (freshness_.accept(delivery.sequence)) {
      // Limits are enforced here, at the axis, whatever the server sent.
      input_ = std::clamp(delivery.payload, -command_limit_, command_limit_);
    }
  }
  plant_->advance(end_time_s - time_s_, input_);
  time_s_ = end_time_s;
}

}  // namespace netmc::sim
