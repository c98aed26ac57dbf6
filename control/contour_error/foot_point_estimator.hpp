#pragma once
// In-loop contour-error estimation by the foot point on the desired motion (paper 002, sec. 4):
// Newton or Steffensen iterations from the reference's own time each cycle (stateless, so a lost
// or late cycle never leaves a stale warm start). The error is signed like the other estimators
// (positive on the right of the direction of travel) and (cx, cy) is the right-hand unit normal
// at the foot point, so the error vector P - C(t*) is eps (cx, -cy) (contour_error_vector).

#include <memory>

#include "control/contour_error/contour_error_estimator.hpp"
#include "control/trajectory/foot_point.hpp"

namespace netmc::control {

enum class FootPointMethod { newton, steffensen };

class FootPointContourErrorEstimator final : public ContourErrorEstimator {
 public:
  FootPointContourErrorEstimator(FootPointMethod method, std::shared_ptr<const ReferenceTrajectory> trajectory,
                                 FootPointOptions options = {});

  ContourErrorEstimate estimate(const ReferencePoint& reference, const Eigen::Vector2d& measured) const override;
  std::unique_ptr<ContourErrorEstimator> clone() const override;
  std::string name() const override;

 private:
  FootPointMethod method_;
  std::shared_ptr<const ReferenceTrajectory> trajectory_;
  FootPointOptions options_;
};

}  // namespace netmc::control
