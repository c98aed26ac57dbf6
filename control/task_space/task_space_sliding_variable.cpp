#include "control/task_space/task_space_sliding_variable.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

TaskSpaceSlidingVariable::TaskSpaceSlidingVariable(const Eigen::Vector2d& lambda,
                                                   double sample_period_s,
                                                   std::shared_ptr<const TaskFrame> frame,
                                                   const InitializationFilterSettings& filter,
                                                   LocalFrameRate local_rate)
    : lambda_(lambda),
      h_(require_positive(sample_period_s, "sample period")),
      frame_(std::move(frame)),
      local_rate_(local_rate),
      filter_settings_(filter) {
  for (int i = 0; i < 2; ++i) require_positive(lambda[i], "task-space lambda");
  if (filter.enabled) {
    if (!frame_) {
      throw std::invalid_argument(
          "initialization filter: needs the global task frame (gtcf-...), not the local one");
    }
    filter_.emplace(filter.contour_bandwidth, filter.tangential_bandwidth);
  }
}

void TaskSpaceSlidingVariable::reset() {
  samples_seen_ = 0;
  previous_equivalent_velocity_.setZero();
}

SlidingState TaskSpaceSlidingVariable::update(std::size_t cycle, const ReferencePoint& reference,
                                              const Eigen::Vector2d& q) {
  SlidingState out;
  if (samples_seen_ == 1) out.velocity = (q - previous_position_) / h_;
  if (samples_seen_ >= 2) out.velocity = (3.0 * q - 4.0 * previous_position_ + earlier_position_) / (2.0 * h_);

  // Error, Jacobian and desired task velocity in the chosen frame.
  Eigen::Vector2d desired_rate;
  const double speed = reference.velocity.norm();
  if (frame_) {
    // GTCF (eq. 2-50): r_d = [0, rm(q_d)], r_d' = [0, |q_d'|] (rm is arc length along travel).
    // The foot points are followed along the contour from cycle to cycle (the global search
    // alone would jump between branches where a contour crosses itself).
    const TaskCoordinates desired = samples_seen_ == 0
                                        ? frame_->at(reference.position)
                                        : frame_->near(reference.position, desired_rm_ + speed * h_);
    const TaskCoordinates actual = frame_->near(q, desired.rm);
    desired_rm_ = desired.rm;
    const double perimeter = frame_->perimeter_m();
    const auto wrap = [perimeter](double d) { return perimeter > 0.0 ? std::remainder(d, perimeter) : d; };
    out.jacobian = actual.jacobian;
    if (filter_) {
      // eq. 2-67: r_i = r_d + z, started at r_i(0) = r(q(0)), r_i'(0) = 0. The tangential error
      // is wrapped once, after z is added, so that it stays continuous however far r_mi moves
      // from r_md on a closed contour (netmc's assumption [A]).
      if (samples_seen_ == 0) {
        first_cycle_ = cycle;
        filter_->start({actual.rc, wrap(actual.rm - desired.rm)}, {0.0, -speed});
      }
      const FilterOffset z = filter_->offset(static_cast<double>(cycle - first_cycle_) * h_);
      out.error << actual.rc - z.value[0], wrap(actual.rm - desired.rm - z.value[1]);
      desired_rate << z.rate[0], speed + z.rate[1];
    } else {
      out.error << actual.rc, wrap(actual.rm - desired.rm);  // across the seam
      desired_rate << 0.0, speed;
    }
  } else {
    // LTCF (eq. 2-61..2-64): T(alpha) at the desired point, T^-1 = T.
    const double alpha = std::atan2(reference.velocity.y(), reference.velocity.x());
    out.jacobian << -std::sin(alpha), std::cos(alpha), std::cos(alpha), std::sin(alpha);
    out.error = out.jacobian * (q - reference.position);
    desired_rate = out.jacobian * reference.velocity;
    if (local_rate_ == LocalFrameRate::rotating && speed > 0.0) {
      // T' = alpha' dT/dalpha with alpha' = (v x a) / |v|^2 of the desired motion; moving T' e
      // into the desired rate makes s = e' + Lambda e and q_eq' = q_d' - T (T' + Lambda T) e
      // (netmc's reconstruction [A]: the thesis does not give its LTCF controllers' design). At the
      // ellipse's vertices alpha' reaches 70 rad/s.
      const Eigen::Vector2d& v = reference.velocity;
      const Eigen::Vector2d& a = reference.acceleration;
      const double alpha_rate = (v.x() * a.y() - v.y() * a.x()) / (speed * speed);
      Eigen::Matrix2d turning;  // dT/dalpha
      turning << -std::cos(alpha), -std::sin(alpha), -std::sin(alpha), std::cos(alpha);
      desired_rate -= alpha_rate * turning * (q - reference.position);
    }
  }
  out.inverse = out.jacobian.inverse();
  const Eigen::Vector2d lambda_error = lambda_.cwiseProduct(out.error);
  out.s = out.jacobian * out.velocity - desired_rate + lambda_error;  // eq. 2-50
  const Eigen::Vector2d equivalent_velocity = out.inverse * (desired_rate - lambda_error);
  if (samples_seen_ > 0) out.equivalent_acceleration = (equivalent_velocity - previous_equivalent_velocity_) / h_;

  earlier_position_ = samples_seen_ == 0 ? q : previous_position_;
  previous_position_ = q;
  ++samples_seen_;
  previous_equivalent_velocity_ = equivalent_velocity;
  return out;
}

std::string TaskSpaceSlidingVariable::filter_description() const {
  std::ostringstream text;
  if (!frame_ && local_rate_ == LocalFrameRate::rotating) text << ", rotating frame";
  if (filter_) {
    text << ", init filter wc=" << filter_settings_.contour_bandwidth
         << " wm=" << filter_settings_.tangential_bandwidth;
  }
  return text.str();
}

}  // namespace netmc::control
