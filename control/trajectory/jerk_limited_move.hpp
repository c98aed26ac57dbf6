#pragma once
// A rest-to-rest move over a distance with limited speed, acceleration and jerk: the seven-phase
// S-curve (jerk +J, 0, -J while accelerating, a cruise, the mirror image while decelerating),
// with the constant-acceleration and cruise phases dropped where the distance is too short to
// reach the limits. Symmetric in time, so the deceleration is the acceleration played backwards
// and measured back from the end: the move ends exactly at the distance.

namespace netmc::control {

struct MoveState {
  double position = 0.0;      // m along the move
  double speed = 0.0;         // m/s
  double acceleration = 0.0;  // m/s^2
};

class JerkLimitedMove {
 public:
  // Throws std::invalid_argument naming the limit for a non-positive or non-finite value.
  JerkLimitedMove(double distance_m, double max_speed_m_s, double max_acceleration_m_s2, double max_jerk_m_s3);

  double duration_s() const { return 2.0 * accelerate_s_ + cruise_s_; }
  // Clamped to [0, duration]: at rest at 0 before, at rest at the distance after.
  MoveState at(double time_s) const;

  double distance_m() const { return distance_; }
  double peak_speed_m_s() const { return peak_speed_; }
  double peak_acceleration_m_s2() const { return peak_acceleration_; }
  double jerk_time_s() const { return jerk_s_; }                    // each jerk phase
  double constant_acceleration_time_s() const { return constant_s_; }
  double cruise_time_s() const { return cruise_s_; }

 private:
  MoveState accelerating(double time_s) const;  // the first 2 jerk_s_ + constant_s_

  double distance_, jerk_;
  double jerk_s_ = 0.0, constant_s_ = 0.0, accelerate_s_ = 0.0, cruise_s_ = 0.0;
  double peak_speed_ = 0.0, peak_acceleration_ = 0.0;
};

}  // namespace netmc::control
