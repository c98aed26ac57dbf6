#pragma once
// Contour-error estimators used by the controllers (they see only the reference and the
// measurement; the ground truth for metrics is ReferenceTrajectory::contour_error).
// Convention of paper 001: axis errors e = reference - measured and eps ~ -cx*ex + cy*ey, so eps
// is positive on the right of the direction of travel (outside for a counter-clockwise circle).

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct ContourErrorEstimate {
  double contour_error = 0.0;   // eps [m]
  double cx = 0.0;              // cross-coupling gains of eq. 11/13
  double cy = 0.0;
  int iterations = 0;           // foot-point updates of an iterative estimator, else 0
};

// The estimated contour-error vector (measured point minus its foot point): eps along the
// right-hand normal (cx, -cy), exact for the foot-point estimators and first order for the others.
inline Eigen::Vector2d contour_error_vector(const ContourErrorEstimate& e) {
  return e.contour_error * Eigen::Vector2d(e.cx, -e.cy);
}

class ContourErrorEstimator {
 public:
  virtual ~ContourErrorEstimator() = default;
  virtual ContourErrorEstimate estimate(const ReferencePoint& reference,
                                        const Eigen::Vector2d& measured) const = 0;
  virtual std::unique_ptr<ContourErrorEstimator> clone() const = 0;
  virtual std::string name() const = 0;
};

// First order, tangent line at the desired point: cx = sin(theta), cy = cos(theta)
// (paper 001, eq. 11; exact for lines).
class TangentContourErrorEstimator final : public ContourErrorEstimator {
 public:
  ContourErrorEstimate estimate(const ReferencePoint& reference,
                                const Eigen::Vector2d& measured) const override;
  std::unique_ptr<ContourErrorEstimator> clone() const override;
  std::string name() const override { return "tangent"; }
};

// Second order with the osculating circle at the desired point, radius 1/kappa from the
// reference velocity and acceleration: cx = sin(theta) - kappa*ex/2, cy = cos(theta) + kappa*ey/2
// (paper 001, eq. 13 for a circle; reduces to eq. 11 where the contour is straight).
class CurvatureContourErrorEstimator final : public ContourErrorEstimator {
 public:
  ContourErrorEstimate estimate(const ReferencePoint& reference,
                                const Eigen::Vector2d& measured) const override;
  std::unique_ptr<ContourErrorEstimator> clone() const override;
  std::string name() const override { return "curvature"; }
};

// tangent, curvature, newton, steffensen
std::vector<std::string> contour_error_estimator_names();
// Throws std::invalid_argument naming the field for an unknown name. The foot-point estimators
// (newton, steffensen; foot_point_estimator.hpp) search `trajectory`, which they then need.
std::unique_ptr<ContourErrorEstimator> make_contour_error_estimator(
    std::string_view name, std::shared_ptr<const ReferenceTrajectory> trajectory = nullptr);

}  // namespace netmc::control
