#pragma once
// A move of one axis from where it is, at whatever speed, to a position at rest: first a stop at
// the acceleration limit, then the time-optimal trapezoid (or triangle) under the velocity and
// acceleration limits. An axis node streams its positions as CSP targets to bring a drive to an
// iteration's start (hardware cannot be reset to it as a simulation is).

namespace netmc::drive {

class PointToPointMove {
 public:
  // Throws std::invalid_argument for a non-finite position or velocity, or a limit that is not a
  // positive finite number.
  PointToPointMove(double from_m, double from_velocity_m_s, double to_m, double velocity_m_s,
                   double acceleration_m_s2);

  double duration_s() const { return stop_s_ + accelerate_s_ + cruise_s_ + accelerate_s_; }
  double position_m(double t_s) const;   // t from the move's start; the target after its end
  double velocity_m_s(double t_s) const;

 private:
  double from_m_, from_velocity_m_s_, to_m_, acceleration_m_s2_;
  double stop_s_ = 0.0, stop_position_m_ = 0.0;   // the stop
  double direction_ = 1.0, peak_m_s_ = 0.0;       // the trapezoid towards to_m
  double accelerate_s_ = 0.0, cruise_s_ = 0.0;
};

}  // namespace netmc::drive
