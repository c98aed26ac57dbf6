#include "plant/piecewise_axis_plant.hpp"

#include "plant/parameter_checks.hpp"

namespace netmc::plant {

void PiecewiseAxisPlant::reset(double position, double velocity) {
  require_finite(owner_, "position", position);
  require_finite(owner_, "velocity", velocity);
  reset_state(position, velocity);
  time_ = 0.0;
}

void PiecewiseAxisPlant::advance(double duration_s, double input) {
  require_advance_arguments(owner_, duration_s, input);
  if (duration_s == 0.0) return;
  for_each_smooth_piece(
      disturbance(), time_, duration_s,
      [&](double t0, double dt, double step_level) { advance_piece(t0, dt, input, step_level); });
  time_ += duration_s;
}

}  // namespace netmc::plant
