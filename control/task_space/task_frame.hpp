#pragma once
// Global task coordinate frame (thesis, paper 000, ch. 2): coordinates r = [rc, rm] of a point q
// in the plane, where rc is the contour error exact to first order (2-11) and rm the arc length
// along the contour (2-21), with the Jacobian J = d r / d q, orthonormal on the contour.
// Closed forms for the circle (2-34..2-36) and the ellipse (2-40..2-42), and a numerical
// construction from any desired motion through its exact foot point.

#include <Eigen/Dense>
#include <memory>
#include <vector>

#include "control/trajectory/foot_point.hpp"
#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct TaskCoordinates {
  double rc = 0.0;                                   // contour coordinate [m], positive outside
  double rm = 0.0;                                   // arc length from the contour's origin [m]
  Eigen::Matrix2d jacobian = Eigen::Matrix2d::Zero();  // rows: grad rc, grad rm
};

class TaskFrame {
 public:
  virtual ~TaskFrame() = default;
  virtual TaskCoordinates at(const Eigen::Vector2d& q) const = 0;
  // The same with the foot point sought along the contour near arc length `rm_hint` (e.g. where
  // the motion was a cycle ago), for contours that come back near themselves, where the global
  // foot point would jump to another branch. Frames with a unique foot point ignore the hint.
  virtual TaskCoordinates near(const Eigen::Vector2d& q, double /*rm_hint*/) const { return at(q); }
  // Length of a closed contour (rm wraps at it); 0 for an open one.
  virtual double perimeter_m() const = 0;
};

// rc = |q - c| - R, rm = R atan2 (counter-clockwise arc length), J = [e_r; e_theta * R/rho].
// Clockwise: rm = -R atan2 and the second row of J negated, so that rm grows along the motion
// (netmc's assumption [A], for the thesis's case B of section 2.5.4.1).
class CircleTaskFrame final : public TaskFrame {
 public:
  CircleTaskFrame(const Eigen::Vector2d& center, double radius, bool clockwise = false);
  TaskCoordinates at(const Eigen::Vector2d& q) const override;
  double perimeter_m() const override;

 private:
  Eigen::Vector2d center_;
  double radius_;
  bool clockwise_;
};

// rc of (2-42); rm = s(nu) of the point projected onto the contour along grad f (2-21), with the
// arc length s(nu) tabulated; J by the analytic gradient of rc and s'(nu) grad nu.
class EllipseTaskFrame final : public TaskFrame {
 public:
  EllipseTaskFrame(const Eigen::Vector2d& center, double semi_axis_x, double semi_axis_y);
  TaskCoordinates at(const Eigen::Vector2d& q) const override;
  double perimeter_m() const override { return arc_table_.back(); }
  double arc_length(double nu) const;  // from nu = 0, counter-clockwise

 private:
  double rc(const Eigen::Vector2d& local) const;
  double parameter(const Eigen::Vector2d& local) const;  // nu of the projected point

  Eigen::Vector2d center_;
  double a_, b_;
  std::vector<double> arc_table_;  // s at nu = 2 pi i / N
};

// Any desired motion: rc = signed distance to the exact foot point, rm = arc length to it,
// J = [outward normal; tangent] at the foot point (exact on the contour). Where the motion stops
// at the foot point (a sharp corner), the side is taken from the chord through it and the
// normal is the gradient of the distance.
class NumericalTaskFrame final : public TaskFrame {
 public:
  explicit NumericalTaskFrame(std::shared_ptr<const ReferenceTrajectory> contour);
  TaskCoordinates at(const Eigen::Vector2d& q) const override;
  // Searches the samples within 5 % of the contour's length of `rm_hint`.
  TaskCoordinates near(const Eigen::Vector2d& q, double rm_hint) const override;
  // Closed when the motion ends where it starts.
  double perimeter_m() const override;

 private:
  std::shared_ptr<const ReferenceTrajectory> contour_;
  std::vector<double> arc_table_;  // s at t = duration i / N
  TaskCoordinates coordinates(const Eigen::Vector2d& q, const FootPoint& foot) const;
  std::size_t sample_index(double rm) const;  // the grid sample at arc length rm

  SampledContour grid_;            // the global search's samples, taken once
};

}  // namespace netmc::control
