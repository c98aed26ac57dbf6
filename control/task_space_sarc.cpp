#include "control/task_space_sarc.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {

TaskSpaceSarc::TaskSpaceSarc(const SarcGains& gains, double sample_period_s,
                             std::shared_ptr<const TaskFrame> frame)
    : gains_(gains), h_(require_positive(sample_period_s, "sample period")), frame_(std::move(frame)) {
  for (int i = 0; i < 2; ++i) {
    require_positive(gains.mass[i], "sarc mass");
    require_non_negative(gains.damping[i], "sarc damping");
    require_non_negative(gains.coulomb[i], "sarc coulomb");
    require_positive(gains.lambda[i], "sarc lambda");
    require_non_negative(gains.feedback[i], "sarc feedback");
    require_non_negative(gains.adaptation[i], "sarc adaptation");
    require_positive(gains.uncertainty_bound[i], "sarc uncertainty bound");
  }
}

void TaskSpaceSarc::begin_iteration(const Eigen::Vector2d& initial_position, std::size_t) {
  previous_position_ = initial_position;
  earlier_position_ = initial_position;
  samples_seen_ = 0;
  previous_equivalent_velocity_.setZero();
  estimate_.setZero();
  first_ = true;
}

ContouringCycle TaskSpaceSarc::step(std::size_t, const ReferencePoint& reference,
                                    const Eigen::Vector2d& q) {
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  if (samples_seen_ == 1) velocity = (q - previous_position_) / h_;
  if (samples_seen_ >= 2) velocity = (3.0 * q - 4.0 * previous_position_ + earlier_position_) / (2.0 * h_);

  // Error, Jacobian and desired task velocity in the chosen frame.
  Eigen::Vector2d error, desired_rate;
  Eigen::Matrix2d jacobian;
  const double speed = reference.velocity.norm();
  if (frame_) {
    // GTCF (eq. 2-50): r_d = [0, rm(q_d)], r_d' = [0, |q_d'|] (rm is arc length along travel).
    // The foot points are followed along the contour from cycle to cycle (the global search
    // alone would jump between branches where a contour crosses itself).
    const TaskCoordinates desired = first_ ? frame_->at(reference.position)
                                           : frame_->near(reference.position, desired_rm_ + speed * h_);
    const TaskCoordinates actual = frame_->near(q, desired.rm);
    desired_rm_ = desired.rm;
    double tangential = actual.rm - desired.rm;
    const double perimeter = frame_->perimeter_m();
    if (perimeter > 0.0) tangential = std::remainder(tangential, perimeter);  // across the seam
    error << actual.rc, tangential;
    jacobian = actual.jacobian;
    desired_rate << 0.0, speed;
  } else {
    // LTCF (eq. 2-61..2-64): T(alpha) at the desired point, T^-1 = T.
    const double alpha = std::atan2(reference.velocity.y(), reference.velocity.x());
    jacobian << -std::sin(alpha), std::cos(alpha), std::cos(alpha), std::sin(alpha);
    error = jacobian * (q - reference.position);
    desired_rate = jacobian * reference.velocity;
  }
  const Eigen::Matrix2d inverse = jacobian.inverse();
  const Eigen::Vector2d lambda_error = gains_.lambda.cwiseProduct(error);
  const Eigen::Vector2d s = jacobian * velocity - desired_rate + lambda_error;        // eq. 2-50
  const Eigen::Vector2d equivalent_velocity = inverse * (desired_rate - lambda_error);
  const Eigen::Vector2d equivalent_acceleration =
      first_ ? Eigen::Vector2d::Zero()
             : Eigen::Vector2d((equivalent_velocity - previous_equivalent_velocity_) / h_);

  // eq. 2-54 and 2-56 (as implemented: u_s = -J^T K_s s)
  Eigen::Vector2d friction;
  for (int i = 0; i < 2; ++i) {
    friction[i] = gains_.coulomb[i] * 2.0 / std::numbers::pi * std::atan(gains_.friction_slope * velocity[i]);
  }
  ContouringCycle out;
  out.command = gains_.mass.cwiseProduct(equivalent_acceleration) + gains_.damping.cwiseProduct(velocity) +
                friction + estimate_ - jacobian.transpose() * gains_.feedback.cwiseProduct(s);
  out.axis_command = out.command;
  out.estimate.contour_error = error[0];

  // eq. 2-58/2-59: gradient adaptation with projection onto |F_l,i| <= F_M,i
  const Eigen::Vector2d direction = inverse * s;
  for (int i = 0; i < 2; ++i) {
    const double rate = -gains_.adaptation[i] * direction[i];
    const bool blocked = (estimate_[i] >= gains_.uncertainty_bound[i] && rate > 0.0) ||
                         (estimate_[i] <= -gains_.uncertainty_bound[i] && rate < 0.0);
    if (!blocked) {
      estimate_[i] = std::clamp(estimate_[i] + h_ * rate, -gains_.uncertainty_bound[i],
                                gains_.uncertainty_bound[i]);
    }
  }
  earlier_position_ = previous_position_;
  previous_position_ = q;
  ++samples_seen_;
  previous_equivalent_velocity_ = equivalent_velocity;
  first_ = false;
  return out;
}

std::string TaskSpaceSarc::describe() const {
  std::ostringstream text;
  text << (frame_ ? "gtcf" : "ltcf") << "-sarc(lambda=" << gains_.lambda.transpose()
       << ", Ks=" << gains_.feedback.transpose() << ", Gamma=" << gains_.adaptation.transpose() << ")";
  return text.str();
}

}  // namespace netmc::control
