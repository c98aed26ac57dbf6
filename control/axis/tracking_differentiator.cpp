#include "control/axis/tracking_differentiator.hpp"

#include "control/parameter_check.hpp"

namespace netmc::control {

TrackingDifferentiator::TrackingDifferentiator(double speed_factor, double sample_period_s)
    : r0_(require_positive(speed_factor, "tracking differentiator r0")),
      h_(require_positive(sample_period_s, "sample period")) {}

void TrackingDifferentiator::reset(double position, double velocity) {
  v1_ = position;
  v2_ = velocity;
}

void TrackingDifferentiator::update(double reference) {
  // paper 001, eq. 8
  const double tracking_error = v1_ - reference;
  const double v1_next = v1_ + h_ * v2_;
  const double v2_next = v2_ + h_ * (-r0_ * r0_ * tracking_error - 2.0 * r0_ * v2_);
  v1_ = v1_next;
  v2_ = v2_next;
}

}  // namespace netmc::control
