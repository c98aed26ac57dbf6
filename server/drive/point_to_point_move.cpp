#include "server/drive/point_to_point_move.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace netmc::drive {

PointToPointMove::PointToPointMove(double from_m, double from_velocity_m_s, double to_m, double velocity_m_s,
                                   double acceleration_m_s2)
    : from_m_(from_m), from_velocity_m_s_(from_velocity_m_s), to_m_(to_m), acceleration_m_s2_(acceleration_m_s2) {
  if (!std::isfinite(from_m) || !std::isfinite(from_velocity_m_s) || !std::isfinite(to_m)) {
    throw std::invalid_argument("move: positions and velocity must be finite");
  }
  if (!(velocity_m_s > 0.0) || !std::isfinite(velocity_m_s) || !(acceleration_m_s2 > 0.0) ||
      !std::isfinite(acceleration_m_s2)) {
    throw std::invalid_argument("move: velocity and acceleration limits must be positive finite numbers");
  }
  stop_s_ = std::abs(from_velocity_m_s) / acceleration_m_s2;
  stop_position_m_ = from_m + from_velocity_m_s * stop_s_ / 2.0;
  const double distance = to_m - stop_position_m_;
  direction_ = distance < 0.0 ? -1.0 : 1.0;
  // A triangle if the distance is too short to reach the velocity limit.
  peak_m_s_ = std::min(velocity_m_s, std::sqrt(std::abs(distance) * acceleration_m_s2));
  accelerate_s_ = peak_m_s_ / acceleration_m_s2;
  cruise_s_ = peak_m_s_ > 0.0 ? (std::abs(distance) - peak_m_s_ * accelerate_s_) / peak_m_s_ : 0.0;
  cruise_s_ = std::max(0.0, cruise_s_);
}

double PointToPointMove::velocity_m_s(double t) const {
  const double a = acceleration_m_s2_;
  if (t <= 0.0) return from_velocity_m_s_;
  if (t < stop_s_) return from_velocity_m_s_ - (from_velocity_m_s_ < 0.0 ? -a : a) * t;
  t -= stop_s_;
  double speed = 0.0;
  if (t < accelerate_s_) {
    speed = a * t;
  } else if (t < accelerate_s_ + cruise_s_) {
    speed = peak_m_s_;
  } else if (t < 2.0 * accelerate_s_ + cruise_s_) {
    speed = peak_m_s_ - a * (t - accelerate_s_ - cruise_s_);
  }
  return direction_ * speed;
}

double PointToPointMove::position_m(double t) const {
  const double a = acceleration_m_s2_;
  if (t <= 0.0) return from_m_;
  if (t >= duration_s()) return to_m_;
  if (t < stop_s_) {
    const double brake = from_velocity_m_s_ < 0.0 ? -a : a;
    return from_m_ + from_velocity_m_s_ * t - brake * t * t / 2.0;
  }
  t -= stop_s_;
  double travelled = 0.0;
  if (t < accelerate_s_) {
    travelled = a * t * t / 2.0;
  } else if (t < accelerate_s_ + cruise_s_) {
    travelled = peak_m_s_ * accelerate_s_ / 2.0 + peak_m_s_ * (t - accelerate_s_);
  } else {
    const double left = 2.0 * accelerate_s_ + cruise_s_ - t;  // time to the end
    travelled = std::abs(to_m_ - stop_position_m_) - a * left * left / 2.0;
  }
  return stop_position_m_ + direction_ * travelled;
}

}  // namespace netmc::drive
