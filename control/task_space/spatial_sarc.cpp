#include "control/task_space/spatial_sarc.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "control/estimation/box_projection.hpp"
#include "control/parameter_check.hpp"

namespace netmc::control {

SpatialSarc::SpatialSarc(const SpatialSarcGains& gains, double sample_period_s,
                         std::shared_ptr<const SpatialCircle> contour)
    : gains_(gains), h_(require_positive(sample_period_s, "sample period")), contour_(std::move(contour)) {
  if (!contour_) throw std::invalid_argument("spatial sarc: missing contour");
  for (int i = 0; i < 3; ++i) {
    require_positive(gains.mass[i], "sarc mass");
    require_non_negative(gains.damping[i], "sarc damping");
    require_non_negative(gains.coulomb[i], "sarc coulomb");
    require_positive(gains.lambda[i], "sarc lambda");
    require_non_negative(gains.feedback[i], "sarc feedback");
    require_non_negative(gains.adaptation[i], "sarc adaptation");
    require_positive(gains.uncertainty_bound[i], "sarc uncertainty bound");
  }
}

void SpatialSarc::begin(const Eigen::Vector3d& initial_position) {
  previous_position_ = initial_position;
  earlier_position_ = initial_position;
  samples_seen_ = 0;
  previous_equivalent_velocity_.setZero();
  estimate_.setZero();
  error_.setZero();
}

Eigen::Vector3d SpatialSarc::step(const SpatialReferencePoint& reference, const Eigen::Vector3d& q) {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  if (samples_seen_ == 1) velocity = (q - previous_position_) / h_;
  if (samples_seen_ >= 2) velocity = (3.0 * q - 4.0 * previous_position_ + earlier_position_) / (2.0 * h_);

  // thesis eq. 6-4 and 6-15: e = r(q) - r_d, r_d = [0, 0, rm(q_d)], r_d' = [0, 0, |q_d'|].
  const SpatialTaskCoordinates actual = contour_->at(q);
  const SpatialTaskCoordinates desired = contour_->at(reference.position);
  error_ = actual.r;
  error_[2] = std::remainder(actual.r[2] - desired.r[2], contour_->perimeter_m());  // across the seam
  const Eigen::Vector3d desired_rate(0.0, 0.0, reference.velocity.norm());
  const Eigen::Matrix3d& jacobian = actual.jacobian;
  const Eigen::Matrix3d inverse = jacobian.inverse();
  const Eigen::Vector3d lambda_error = gains_.lambda.cwiseProduct(error_);
  const Eigen::Vector3d s = jacobian * velocity - desired_rate + lambda_error;  // eq. 2-50
  const Eigen::Vector3d equivalent_velocity = inverse * (desired_rate - lambda_error);
  const Eigen::Vector3d equivalent_acceleration =
      samples_seen_ == 0 ? Eigen::Vector3d::Zero()
                         : Eigen::Vector3d((equivalent_velocity - previous_equivalent_velocity_) / h_);

  // eq. 2-54, 2-56 (u_s = -J^T K_s s)
  Eigen::Vector3d friction;
  for (int i = 0; i < 3; ++i) {
    friction[i] = gains_.coulomb[i] * 2.0 / std::numbers::pi * std::atan(gains_.friction_slope * velocity[i]);
  }
  const Eigen::Vector3d command = gains_.mass.cwiseProduct(equivalent_acceleration) +
                                  gains_.damping.cwiseProduct(velocity) + friction + estimate_ -
                                  jacobian.transpose() * gains_.feedback.cwiseProduct(s);

  // eq. 2-58/2-59: gradient adaptation with projection onto |F_l,i| <= F_M,i
  const Eigen::Vector3d direction = inverse * s;
  for (int i = 0; i < 3; ++i) {
    estimate_[i] = projected_step(estimate_[i], -gains_.adaptation[i] * direction[i],
                                  -gains_.uncertainty_bound[i], gains_.uncertainty_bound[i], h_);
  }
  earlier_position_ = previous_position_;
  previous_position_ = q;
  ++samples_seen_;
  previous_equivalent_velocity_ = equivalent_velocity;
  return command;
}

}  // namespace netmc::control
