#include "control/dead_zone/diarc_tracking_loop.hpp"

#include "control/parameter_check.hpp"
#include "control/estimation/box_projection.hpp"

namespace netmc::control {

void DiarcLoopGains::validate() const {
  require_positive(lambda, "controller.lambda");
  require_non_negative(feedback, "controller.feedback");
  require_non_negative(disturbance_adaptation, "controller.disturbance_adaptation");
  require_positive(disturbance_bound, "controller.disturbance_bound");
  require_positive(friction_slope, "controller.friction_slope");
}

DiarcTrackingLoop::DiarcTrackingLoop(const DiarcLoopGains& gains, double sample_period_s)
    : gains_(gains), h_(require_positive(sample_period_s, "controller.sample_period_s")) {
  gains_.validate();
}

void DiarcTrackingLoop::begin(double initial_position_m) {
  previous_ = before_previous_ = initial_position_m;  // at rest before the start
  disturbance_ = 0.0;                                // (5-25): d_c^(0) = 0
  state_ = {};
  regression_ = {};
}

const DiarcLoopState& DiarcTrackingLoop::measure(const AxisReference& reference, double y) {
  // Plain differences, no filter: the thesis differences its encoder; the 2.5 mm/s quantum this
  // leaves in x' passes through k_s s as a 0.5 m/s^2 ripple, well inside what the loop tolerates.
  regression_.acceleration = (y - 2.0 * previous_ + before_previous_) / (h_ * h_);
  regression_.velocity = (y - before_previous_) / (2.0 * h_);
  state_.velocity = (y - previous_) / h_;
  before_previous_ = previous_;
  previous_ = y;

  state_.error = y - reference.position;
  state_.velocity_error = state_.velocity - reference.velocity;
  state_.s = state_.velocity_error + gains_.lambda * state_.error;  // (5-19)
  state_.friction = friction_sign(state_.velocity, gains_.friction_slope);
  state_.demand_without_model = reference.acceleration - gains_.lambda * state_.velocity_error -
                                disturbance_ - gains_.feedback * state_.s;  // (5-22)
  return state_;
}

void DiarcTrackingLoop::adapt_disturbance() {
  disturbance_ = projected_step(disturbance_, gains_.disturbance_adaptation * state_.s,
                                -gains_.disturbance_bound, gains_.disturbance_bound, h_);  // (5-25)
}

}  // namespace netmc::control
