#include "control/contour_error/foot_point_estimator.hpp"

#include <stdexcept>

namespace netmc::control {

FootPointContourErrorEstimator::FootPointContourErrorEstimator(FootPointMethod method,
                                                               std::shared_ptr<const ReferenceTrajectory> trajectory,
                                                               FootPointOptions options)
    : method_(method), trajectory_(std::move(trajectory)), options_(options) {
  if (!trajectory_) throw std::invalid_argument("estimator: the foot-point estimators need the trajectory");
}

ContourErrorEstimate FootPointContourErrorEstimator::estimate(const ReferencePoint& reference,
                                                              const Eigen::Vector2d& measured) const {
  const FootPoint foot = method_ == FootPointMethod::newton
                             ? newton_foot_point(*trajectory_, measured, reference.time_s, options_)
                             : steffensen_foot_point(*trajectory_, measured, reference.time_s, options_);
  // Direction of travel at the foot point; at a cusp (C' = 0) the reference's own.
  Eigen::Vector2d tangent = foot.velocity;
  if (tangent.norm() < 1e-12) tangent = reference.velocity;
  if (tangent.norm() < 1e-12) tangent = Eigen::Vector2d::UnitX();
  tangent.normalize();
  const Eigen::Vector2d normal(tangent.y(), -tangent.x());  // right of travel
  ContourErrorEstimate estimate;
  estimate.cx = normal.x();
  estimate.cy = -normal.y();
  estimate.contour_error = (measured - foot.position).dot(normal);
  estimate.iterations = foot.iterations;
  return estimate;
}

std::unique_ptr<ContourErrorEstimator> FootPointContourErrorEstimator::clone() const {
  return std::make_unique<FootPointContourErrorEstimator>(*this);
}

std::string FootPointContourErrorEstimator::name() const {
  return method_ == FootPointMethod::newton ? "newton" : "steffensen";
}

}  // namespace netmc::control
