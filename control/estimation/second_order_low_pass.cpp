#include "control/estimation/second_order_low_pass.hpp"

#include <Eigen/LU>
#include <numbers>

#include "control/parameter_check.hpp"

namespace netmc::control {

SecondOrderLowPass::SecondOrderLowPass(double cutoff_hz, double damping, double h) {
  const double w = 2.0 * std::numbers::pi * require_positive(cutoff_hz, "diarc filter cut-off");
  require_positive(damping, "diarc filter damping");
  Eigen::Matrix2d a;
  a << 0.0, 1.0, -w * w, -2.0 * damping * w;
  const Eigen::Matrix2d left = (Eigen::Matrix2d::Identity() - 0.5 * h * a).inverse();
  propagate_ = left * (Eigen::Matrix2d::Identity() + 0.5 * h * a);
  drive_ = left * Eigen::Vector2d(0.0, w * w) * (0.5 * h);
}

void SecondOrderLowPass::step(double input) {
  state_ = propagate_ * state_ + drive_ * (previous_input_ + input);
  previous_input_ = input;
}

}  // namespace netmc::control
