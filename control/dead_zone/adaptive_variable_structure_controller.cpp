#include "control/dead_zone/adaptive_variable_structure_controller.hpp"

#include <sstream>

#include "control/dead_zone/diarc_tracking_loop.hpp"
#include "control/parameter_check.hpp"

namespace netmc::control {

void AdaptiveVariableStructureGains::validate() const {
  require_positive(c1, "controller.c1");
  require_positive(c2, "controller.c2");
  require_non_negative(mu, "controller.mu");
  require_non_negative(parameter_adaptation, "controller.parameter_adaptation");
  require_non_negative(beta, "controller.beta");
  require_positive(initial_inverse_gain, "controller.initial_inverse_gain");
  require_finite(initial_parameters[0], "controller.initial_parameters");
  require_finite(initial_parameters[1], "controller.initial_parameters");
  require_positive(friction_slope, "controller.friction_slope");
}

AdaptiveVariableStructureController::AdaptiveVariableStructureController(
    const AdaptiveVariableStructureGains& gains, double sample_period_s)
    : gains_(gains), h_(require_positive(sample_period_s, "controller.sample_period_s")) {
  gains_.validate();
  begin_iteration(0.0, 0);
}

void AdaptiveVariableStructureController::begin_iteration(double initial_position_m, std::size_t) {
  previous_ = initial_position_m;
  inverse_gain_ = gains_.initial_inverse_gain;
  parameters_ = gains_.initial_parameters;
  bound_ = 0.0;
}

double AdaptiveVariableStructureController::step(std::size_t cycle, const AxisReference& reference,
                                                 double y) {
  const double velocity = (y - previous_) / h_;
  previous_ = y;
  const double z1 = y - reference.position;
  const double z1_rate = velocity - reference.velocity;
  const double z2 = z1_rate + gains_.c1 * z1;
  const Eigen::Vector2d phi(-velocity, -friction_sign(velocity, gains_.friction_slope));
  const double sign = z2 > 0.0 ? 1.0 : (z2 < 0.0 ? -1.0 : 0.0);
  // thesis (5-55)
  const double demand = reference.acceleration - gains_.c1 * z1_rate - phi.dot(parameters_) - gains_.c2 * z2 - z1 -
                        sign * bound_;
  const double command = cycle == 0 ? 0.0 : inverse_gain_ * demand;  // v(0) = 0
  inverse_gain_ += h_ * (-gains_.beta * demand * z2);
  parameters_ += h_ * gains_.parameter_adaptation * phi * z2;
  bound_ += h_ * gains_.mu * std::abs(z2);
  return command;
}

std::string AdaptiveVariableStructureController::describe() const {
  std::ostringstream text;
  text << "axis-avsc(c1=" << gains_.c1 << ", c2=" << gains_.c2 << ", mu=" << gains_.mu
       << ", Gamma=" << gains_.parameter_adaptation << ", beta=" << gains_.beta << ")";
  return text.str();
}

std::vector<EstimateName> AdaptiveVariableStructureController::estimate_names() const {
  return {{"e_hat", "V/(m/s^2)"}, {"B_hat", "1/s"}, {"A_hat", "m/s^2"}, {"D_hat", "m/s^2"}};
}

void AdaptiveVariableStructureController::read_estimates(double* out) const {
  out[0] = inverse_gain_;
  out[1] = parameters_[0];
  out[2] = parameters_[1];
  out[3] = bound_;
}

}  // namespace netmc::control
