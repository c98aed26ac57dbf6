#include "control/contour_error/contour_error_estimator.hpp"

#include <cmath>
#include <stdexcept>

#include "control/contour_error/foot_point_estimator.hpp"

namespace netmc::control {
namespace {

// Unit tangent of the desired motion; at rest (start of a move) fall back to the direction of
// the acceleration, then to +x, so that the estimate is always defined.
Eigen::Vector2d travel_direction(const ReferencePoint& reference) {
  const double speed = reference.velocity.norm();
  if (speed > 1e-12) return reference.velocity / speed;
  const double acceleration = reference.acceleration.norm();
  if (acceleration > 1e-12) return reference.acceleration / acceleration;
  return Eigen::Vector2d::UnitX();
}

// Signed curvature of the desired path (positive when turning left).
double path_curvature(const ReferencePoint& reference) {
  const Eigen::Vector2d& v = reference.velocity;
  const Eigen::Vector2d& a = reference.acceleration;
  const double speed = v.norm();
  if (speed <= 1e-12) return 0.0;
  return (v.x() * a.y() - v.y() * a.x()) / (speed * speed * speed);
}

}  // namespace

ContourErrorEstimate TangentContourErrorEstimator::estimate(const ReferencePoint& reference,
                                                            const Eigen::Vector2d& measured) const {
  const Eigen::Vector2d tangent = travel_direction(reference);
  const Eigen::Vector2d error = reference.position - measured;
  ContourErrorEstimate estimate;
  estimate.cx = tangent.y();  // sin(theta)
  estimate.cy = tangent.x();  // cos(theta)
  estimate.contour_error = -estimate.cx * error.x() + estimate.cy * error.y();  // eq. 11
  return estimate;
}

std::unique_ptr<ContourErrorEstimator> TangentContourErrorEstimator::clone() const {
  return std::make_unique<TangentContourErrorEstimator>(*this);
}

ContourErrorEstimate CurvatureContourErrorEstimator::estimate(
    const ReferencePoint& reference, const Eigen::Vector2d& measured) const {
  const Eigen::Vector2d tangent = travel_direction(reference);
  const double curvature = path_curvature(reference);
  const Eigen::Vector2d error = reference.position - measured;
  ContourErrorEstimate estimate;
  estimate.cx = tangent.y() - 0.5 * curvature * error.x();  // eq. 13 with 1/R = kappa
  estimate.cy = tangent.x() + 0.5 * curvature * error.y();
  estimate.contour_error = -estimate.cx * error.x() + estimate.cy * error.y();
  return estimate;
}

std::unique_ptr<ContourErrorEstimator> CurvatureContourErrorEstimator::clone() const {
  return std::make_unique<CurvatureContourErrorEstimator>(*this);
}

std::vector<std::string> contour_error_estimator_names() { return {"tangent", "curvature", "newton", "steffensen"}; }

std::unique_ptr<ContourErrorEstimator> make_contour_error_estimator(
    std::string_view name, std::shared_ptr<const ReferenceTrajectory> trajectory) {
  if (name == "tangent") return std::make_unique<TangentContourErrorEstimator>();
  if (name == "curvature") return std::make_unique<CurvatureContourErrorEstimator>();
  if (name == "newton" || name == "steffensen") {
    if (!trajectory) throw std::invalid_argument("estimator: " + std::string(name) + " needs the trajectory");
    return std::make_unique<FootPointContourErrorEstimator>(
        name == "newton" ? FootPointMethod::newton : FootPointMethod::steffensen, std::move(trajectory));
  }
  throw std::invalid_argument("estimator: unknown name '" + std::string(name).substr(0, 64) +
                              "' (expected one of: tangent, curvature, newton, steffensen)");
}

}  // namespace netmc::control
