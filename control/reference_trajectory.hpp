#pragma once
// A desired motion along a planar contour: the reference the server sends each cycle, and the
// exact geometry used as ground truth for the contour-error metrics.

#include <Eigen/Dense>
#include <memory>
#include <string>

namespace netmc::control {

struct ReferencePoint {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  Eigen::Vector2d acceleration = Eigen::Vector2d::Zero();
};

class ReferenceTrajectory {
 public:
  virtual ~ReferenceTrajectory() = default;

  virtual ReferencePoint sample(double time_s) const = 0;
  virtual double duration_s() const = 0;
  // Exact signed distance from `point` to the whole contour: the ground truth for metrics.
  // Closed curves: positive outside. Open curves: positive on the right of the direction of travel.
  virtual double contour_error(const Eigen::Vector2d& point) const = 0;
  virtual std::unique_ptr<ReferenceTrajectory> clone() const = 0;
  virtual std::string describe() const = 0;
};

}  // namespace netmc::control
