#pragma once
// Uniform motion around a circle (paper 001's experiment: r = 10 mm, centre (50, 50) mm, 8 s).

#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct CircleParameters {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius_m = 0.01;
  double period_s = 8.0;           // one revolution
  double start_angle_rad = 0.0;
  bool clockwise = false;
  double revolutions = 1.0;        // duration = revolutions * period
};

class CircleTrajectory final : public ReferenceTrajectory {
 public:
  explicit CircleTrajectory(const CircleParameters& parameters);

  ReferencePoint sample(double time_s) const override;
  double duration_s() const override;
  double period_s() const override { return p_.period_s; }
  double contour_error(const Eigen::Vector2d& point) const override;  // paper 001, eq. 12
  std::unique_ptr<ReferenceTrajectory> clone() const override;
  std::string describe() const override;
  const CircleParameters& parameters() const { return p_; }

 private:
  CircleParameters p_;
  double angular_rate_;  // signed [rad/s]
};

}  // namespace netmc::control
