#pragma once
// Uniform motion around a circle (paper 001's experiment: r = 10 mm, centre (50, 50) mm, 8 s),
// or, with a ramp, from rest to rest: the angle ramps in and out as a quintic in time (netmc's
// assumption [A] for paper 004's circle) and holds the end point after the duration.

#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct CircleParameters {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius_m = 0.01;
  double period_s = 8.0;           // one revolution
  double start_angle_rad = 0.0;
  bool clockwise = false;
  double revolutions = 1.0;        // duration = revolutions * period
  // > 0: the angular rate ramps up from rest over ramp_s and back down to rest over the last
  // ramp_s of the duration (at most half of it), the same total angle; 0: uniform rate throughout.
  double ramp_s = 0.0;
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
  // The angle travelled from the start and its first two derivatives at `time_s`.
  struct AngleState {
    double angle = 0.0, rate = 0.0, acceleration = 0.0;
  };
  AngleState angle_at(double time_s) const;

 private:
  AngleState ramp_in(double time_s) const;  // 0 <= time_s <= ramp_s

  CircleParameters p_;
  double angular_rate_;  // signed [rad/s]: the cruise rate
};

}  // namespace netmc::control
