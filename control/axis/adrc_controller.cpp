#include "control/axis/adrc_controller.hpp"

#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {

AdrcController::AdrcController(const AdrcGains& gains, double sample_period_s)
    : gains_(gains),
      differentiator_(gains.td_speed_factor, sample_period_s),
      observer_(gains.observer_bandwidth, gains.input_gain, sample_period_s,
                gains.observer_discretization) {
  require_finite(gains.kp, "adrc kp");
  require_finite(gains.kd, "adrc kd");
}

void AdrcController::reset(double position) {
  differentiator_.reset(position);
  observer_.reset(position);
}

double AdrcController::command(double /*reference*/, double /*measured_position*/) const {
  // paper 001, eq. 10: the state errors use the TD and observer states of this cycle.
  const double position_error = differentiator_.position() - observer_.position();
  const double velocity_error = differentiator_.velocity() - observer_.velocity();
  const double feedback = gains_.kp * position_error + gains_.kd * velocity_error;
  return feedback - observer_.disturbance() / observer_.input_gain();
}

void AdrcController::commit(double reference, double measured_position, double own_command,
                            double sent_command) {
  differentiator_.update(reference);
  observer_.update(measured_position,
                   gains_.observer_sees_sent_command ? sent_command : own_command);
}

std::unique_ptr<AxisController> AdrcController::clone() const {
  return std::make_unique<AdrcController>(*this);
}

std::string AdrcController::describe() const {
  std::ostringstream text;
  text << "adrc(r0=" << gains_.td_speed_factor << ", w0=" << gains_.observer_bandwidth
       << ", b0=" << gains_.input_gain << ", kp=" << gains_.kp << ", kd=" << gains_.kd
       << ", observer="
       << (gains_.observer_discretization == Discretization::forward_euler ? "euler" : "zoh")
       << (gains_.observer_sees_sent_command ? ", observer input=sent" : "") << ")";
  return text.str();
}

}  // namespace netmc::control
