#pragma once
// Second-order low-pass w^2 / (s^2 + 2 zeta w s + w^2) by the trapezoidal rule, with the output and
// its derivative: the filter H_f of the thesis's least-squares estimators (paper 000, eq. 3-38 and
// 5-39), whose derivative output gives x''_f without a second difference of positions.

#include <Eigen/Core>

namespace netmc::control {

class SecondOrderLowPass {
 public:
  SecondOrderLowPass(double cutoff_hz, double damping, double sample_period_s);
  void reset() {
    state_.setZero();
    previous_input_ = 0.0;
  }
  // Advance one period with the input moving linearly from the previous value to `input`.
  void step(double input);
  double value() const { return state_[0]; }
  double derivative() const { return state_[1]; }

 private:
  Eigen::Matrix2d propagate_;  // (I - hA/2)^-1 (I + hA/2)
  Eigen::Vector2d drive_;      // (I - hA/2)^-1 B h/2
  Eigen::Vector2d state_ = Eigen::Vector2d::Zero();
  double previous_input_ = 0.0;
};

}  // namespace netmc::control
