#pragma once
// Constant-velocity motion along a straight segment from `start` to `end`.

#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct LineParameters {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d end = Eigen::Vector2d(0.02, 0.01);
  double duration_s = 8.0;
};

class LineTrajectory final : public ReferenceTrajectory {
 public:
  explicit LineTrajectory(const LineParameters& parameters);

  ReferencePoint sample(double time_s) const override;
  double duration_s() const override;
  // Distance to the segment; positive on the right of the direction of travel (paper 001, eq. 11).
  double contour_error(const Eigen::Vector2d& point) const override;
  std::unique_ptr<ReferenceTrajectory> clone() const override;
  std::string describe() const override;

 private:
  LineParameters p_;
  Eigen::Vector2d direction_;  // unit
  double length_;
};

}  // namespace netmc::control
