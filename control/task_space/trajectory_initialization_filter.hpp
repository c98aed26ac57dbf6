#pragma once
// Trajectory initialization filter (thesis, paper 000, eq. 2-67): to start with a large error
// without saturating, the controller tracks r_i = [r_ci, r_mi] instead of r_d = [0, r_md]:
//   r_ci'' + 2 wc r_ci' + wc^2 r_ci = 0,
//   r_mi'' + 2 wm r_mi' + wm^2 r_mi = r_md'' + 2 wm r_md' + wm^2 r_md,
// started at r_i(0) = r(q(0)), r_i'(0) = 0 (stage at rest, netmc's assumption [A]), so the initial
// error with respect to r_i is zero. Since r_cd = 0 and r_md enters through the same operator as
// r_mi, the offset z = r_i - r_d obeys the homogeneous equation z'' + 2 w z' + w^2 z = 0 in each
// coordinate, solved exactly: z(t) = (z0 + (z0' + w z0) t) e^(-w t). Working on the offset needs
// no r_md'' and lets the caller add z to an r_md that wraps on a closed contour.

#include <Eigen/Dense>

namespace netmc::control {

struct InitializationFilterSettings {
  bool enabled = false;
  double contour_bandwidth = 8.0;     // wc [rad/s], stiff contour dynamics
  double tangential_bandwidth = 1.0;  // wm [rad/s], soft tangential dynamics
};

struct FilterOffset {
  Eigen::Vector2d value = Eigen::Vector2d::Zero();         // z = r_i - r_d
  Eigen::Vector2d rate = Eigen::Vector2d::Zero();          // z'
  Eigen::Vector2d acceleration = Eigen::Vector2d::Zero();  // z''
};

class TrajectoryInitializationFilter {
 public:
  // Throws std::invalid_argument naming the bandwidth when one is not positive.
  TrajectoryInitializationFilter(double contour_bandwidth, double tangential_bandwidth);

  // Offset and its rate at t = 0: z0 = r(q(0)) - r_d(0), z0' = r_i'(0) - r_d'(0) = -r_d'(0).
  void start(const Eigen::Vector2d& initial_offset, const Eigen::Vector2d& initial_offset_rate);
  // Exact offset at time t >= 0 after the start.
  FilterOffset offset(double time_s) const;

 private:
  Eigen::Vector2d bandwidth_;
  Eigen::Vector2d initial_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d initial_rate_ = Eigen::Vector2d::Zero();
};

}  // namespace netmc::control
