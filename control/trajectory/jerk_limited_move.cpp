#include "control/trajectory/jerk_limited_move.hpp"

#include <algorithm>
#include <cmath>

#include "control/parameter_check.hpp"

namespace netmc::control {

JerkLimitedMove::JerkLimitedMove(double distance_m, double max_speed_m_s, double max_acceleration_m_s2,
                                 double max_jerk_m_s3)
    : distance_(require_positive(distance_m, "move distance")), jerk_(require_positive(max_jerk_m_s3, "max jerk")) {
  const double v = require_positive(max_speed_m_s, "max speed");
  const double a = require_positive(max_acceleration_m_s2, "max acceleration");
  const double j = jerk_;
  // Speeds up to a^2/j are reached without a constant-acceleration phase.
  const auto accelerate_to = [&](double speed) {
    jerk_s_ = std::min(a / j, std::sqrt(speed / j));
    peak_acceleration_ = j * jerk_s_;
    constant_s_ = std::max(0.0, speed / peak_acceleration_ - jerk_s_);
    peak_speed_ = speed;
    accelerate_s_ = 2.0 * jerk_s_ + constant_s_;
  };
  accelerate_to(v);
  // Accelerating and decelerating cover peak speed x accelerate_s_ (the speed is symmetric
  // about half the peak); a short move peaks below the speed limit, where that equals the distance.
  if (peak_speed_ * accelerate_s_ > distance_) {
    const double without_constant = std::pow(0.5 * distance_ * std::sqrt(j), 2.0 / 3.0);  // L = 2 v^1.5 / sqrt(j)
    const double with_constant = 0.5 * a * (-a / j + std::sqrt(a * a / (j * j) + 4.0 * distance_ / a));  // L = v (a/j + v/a)
    accelerate_to(without_constant <= a * a / j ? without_constant : with_constant);
  }
  cruise_s_ = std::max(0.0, (distance_ - peak_speed_ * accelerate_s_) / peak_speed_);
}

MoveState JerkLimitedMove::accelerating(double t) const {
  if (t <= jerk_s_) return {jerk_ * t * t * t / 6.0, 0.5 * jerk_ * t * t, jerk_ * t};
  const double v1 = 0.5 * jerk_ * jerk_s_ * jerk_s_;
  if (t <= jerk_s_ + constant_s_) {
    const double u = t - jerk_s_;
    return {jerk_ * jerk_s_ * jerk_s_ * jerk_s_ / 6.0 + v1 * u + 0.5 * peak_acceleration_ * u * u,
            v1 + peak_acceleration_ * u, peak_acceleration_};
  }
  // The jerk-down phase mirrors the jerk-up phase about (accelerate_s_/2, peak speed/2).
  const double left = accelerate_s_ - t;
  return {0.5 * peak_speed_ * accelerate_s_ - (peak_speed_ * left - jerk_ * left * left * left / 6.0),
          peak_speed_ - 0.5 * jerk_ * left * left, jerk_ * left};
}

MoveState JerkLimitedMove::at(double time_s) const {
  const double t = std::clamp(time_s, 0.0, duration_s());
  if (t <= accelerate_s_) return accelerating(t);
  if (t <= accelerate_s_ + cruise_s_) return {0.5 * peak_speed_ * accelerate_s_ + peak_speed_ * (t - accelerate_s_), peak_speed_, 0.0};
  const MoveState mirrored = accelerating(duration_s() - t);
  return {distance_ - mirrored.position, mirrored.speed, -mirrored.acceleration};
}

}  // namespace netmc::control
