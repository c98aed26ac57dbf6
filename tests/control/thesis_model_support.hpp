#pragma once
// Shared by the thesis (paper 000) ch. 3 tests: the Exp I ellipse (eq. 3-48) and a plant with
// exactly the controllers' model structure (eq. 3-2), M q'' + B q' + A S_f(q') = u + d_n.

#include <cmath>
#include <numbers>

#include "control/trajectory/ellipse_trajectory.hpp"
#include "control/task_space/task_space_darc.hpp"

namespace netmc::control::thesis_support {

// x = 0.2 sin 4t, y = 0.1 - 0.1 cos 4t.
inline EllipseTrajectory exp_i_ellipse(double revolutions) {
  EllipseParameters p;
  p.center = {0.0, 0.1};
  p.semi_axis_x_m = 0.2;
  p.semi_axis_y_m = 0.1;
  p.period_s = 2.0 * std::numbers::pi / 4.0;
  p.start_angle_rad = -std::numbers::pi / 2.0;
  p.revolutions = revolutions;
  return EllipseTrajectory(p);
}

struct ModelPlant {
  ParameterVector theta;
  Eigen::Vector2d q = Eigen::Vector2d::Zero(), v = Eigen::Vector2d::Zero();
  Eigen::Vector2d acceleration(const Eigen::Vector2d& velocity, const Eigen::Vector2d& u) const {
    Eigen::Vector2d a;
    for (int i = 0; i < 2; ++i) {
      const double friction = theta[4 + i] * 2.0 / std::numbers::pi * std::atan(9000.0 * velocity[i]);
      a[i] = (u[i] + theta[6 + i] - theta[2 + i] * velocity[i] - friction) / theta[i];
    }
    return a;
  }
  void advance(const Eigen::Vector2d& u, double h) {  // RK4, 10 sub-steps (friction is stiff)
    const double dt = h / 10.0;
    for (int n = 0; n < 10; ++n) {
      const Eigen::Vector2d k1q = v, k1v = acceleration(v, u);
      const Eigen::Vector2d k2q = v + 0.5 * dt * k1v, k2v = acceleration(k2q, u);
      const Eigen::Vector2d k3q = v + 0.5 * dt * k2v, k3v = acceleration(k3q, u);
      const Eigen::Vector2d k4q = v + dt * k3v, k4v = acceleration(k4q, u);
      q += dt / 6.0 * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
      v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
  }
};

}  // namespace netmc::control::thesis_support
