#include "control/axis/pid_axis_controller.hpp"

#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {

PidAxisController::PidAxisController(const PidAxisGains& gains, double sample_period_s)
    : gains_(gains), h_(require_positive(sample_period_s, "sample period")) {
  require_finite(gains.kp, "pid kp");
  require_finite(gains.ki, "pid ki");
  require_finite(gains.kd, "pid kd");
}

void PidAxisController::reset(double /*position*/) {
  integral_ = 0.0;
  previous_error_ = 0.0;
}

double PidAxisController::command(double reference, double measured_position) const {
  const double error = reference - measured_position;
  return gains_.kp * error + gains_.ki * (integral_ + h_ * error) +
         gains_.kd * (error - previous_error_) / h_;
}

void PidAxisController::commit(double reference, double measured_position, double /*own*/,
                               double /*sent*/) {
  const double error = reference - measured_position;
  integral_ += h_ * error;
  previous_error_ = error;
}

std::unique_ptr<AxisController> PidAxisController::clone() const {
  return std::make_unique<PidAxisController>(*this);
}

std::string PidAxisController::describe() const {
  std::ostringstream text;
  text << "pid(kp=" << gains_.kp << ", ki=" << gains_.ki << ", kd=" << gains_.kd << ")";
  return text.str();
}

}  // namespace netmc::control
