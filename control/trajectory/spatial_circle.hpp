#pragma once
// A circle in three-axis space and its global task coordinate frame (thesis, paper 000, ch. 6).
// The contour is the intersection of two surfaces (eq. 6-3): the sphere |q - c| = R and the plane
// through c with unit normal n (the thesis's example, eq. 6-5..6-7, is c = 0, n along y - x).
// Task coordinates (eq. 6-4): rc1 = |q - c| - R (6-5), rc2 = n . (q - c) (6-6), both normalised
// so that their gradients are unit vectors, and rm = R * angle of q - c in the plane, measured
// from `start` in the direction of motion (arc length on the contour, the role of 6-7 without its
// half-plane restriction). On the contour J = d r / d q is orthonormal here, which the thesis
// notes is not guaranteed for n >= 3 in general.

#include <Eigen/Dense>
#include <string>

namespace netmc::control {

struct SpatialReferencePoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
};

struct SpatialTaskCoordinates {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();         // [rc1, rc2, rm] in m
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();  // rows: grad rc1, grad rc2, grad rm
};

struct SpatialCircleParameters {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius_m = 0.05;
  Eigen::Vector3d normal = Eigen::Vector3d(-1.0, 1.0, 0.0);  // plane y = x (thesis eq. 6-6)
  Eigen::Vector3d start = Eigen::Vector3d(0.0, 0.0, 1.0);    // direction of the start point
  double period_s = 2.0;                                     // one revolution
};

class SpatialCircle {
 public:
  // Throws std::invalid_argument for a non-positive radius or period, a zero normal, or a start
  // direction parallel to the normal.
  explicit SpatialCircle(const SpatialCircleParameters& parameters);

  // Uniform motion from the start point, counter-clockwise about the normal.
  SpatialReferencePoint sample(double time_s) const;
  // Exact distance from q to the circle (ground truth, >= 0).
  double distance(const Eigen::Vector3d& q) const;
  // Undefined on the normal line through the centre (throws std::invalid_argument there).
  SpatialTaskCoordinates at(const Eigen::Vector3d& q) const;
  double perimeter_m() const;
  double period_s() const { return period_s_; }  // one revolution
  std::string describe() const;

 private:
  Eigen::Vector3d center_, normal_, first_, second_;  // first_, second_: in-plane basis
  double radius_, rate_;                              // rate_: rad/s
  double period_s_;
};

}  // namespace netmc::control
