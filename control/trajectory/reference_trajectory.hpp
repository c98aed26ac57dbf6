#pragma once
// A desired motion along a planar contour: the reference the server sends each cycle, and the
// exact geometry used as ground truth for the contour-error metrics.

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

namespace netmc::control {

struct ReferencePoint {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  Eigen::Vector2d acceleration = Eigen::Vector2d::Zero();
  double time_s = 0.0;  // the reference's time, for estimators that search the trajectory near it
};

class ReferenceTrajectory {
 public:
  virtual ~ReferenceTrajectory() = default;

  virtual ReferencePoint sample(double time_s) const = 0;
  virtual double duration_s() const = 0;
  // One pass of a repeating reference (a revolution); the whole run otherwise.
  virtual double period_s() const { return duration_s(); }
  // Exact signed distance from `point` to the whole contour: the ground truth for metrics.
  // Closed curves: positive outside. Open curves: positive on the right of the direction of travel.
  virtual double contour_error(const Eigen::Vector2d& point) const = 0;
  // Times of the sharp corners of the contour (cusps, vertices): where its tangent turns by a
  // finite angle and local foot-point iterations cannot cross. Empty for a smooth contour.
  virtual std::vector<double> corner_times_s() const { return {}; }
  // The motion whose contour this one traces (itself, unless it only re-times another motion,
  // as HaltedTrajectory does): task frames are built from its closed form.
  virtual const ReferenceTrajectory& geometry() const { return *this; }
  virtual std::unique_ptr<ReferenceTrajectory> clone() const = 0;
  virtual std::string describe() const = 0;
};

class TaskFrame;
// The global task frame of a trajectory's contour, with rm increasing along the motion: the
// closed form where there is one, else the numerical construction (slow: a global search).
std::shared_ptr<const TaskFrame> make_task_frame(const ReferenceTrajectory& trajectory);

}  // namespace netmc::control
