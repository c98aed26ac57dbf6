#include "control/cross_coupling/pid_cross_coupling.hpp"

#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {

PidCrossCoupling::PidCrossCoupling(const PidCrossCouplingGains& gains, double sample_period_s)
    : gains_(gains), h_(require_positive(sample_period_s, "sample period")) {
  require_finite(gains.kp, "pidccc kp");
  require_finite(gains.ki, "pidccc ki");
  require_finite(gains.kd, "pidccc kd");
}

void PidCrossCoupling::begin_iteration(std::size_t /*samples*/) {
  integral_ = 0.0;
  previous_error_ = 0.0;
}

double PidCrossCoupling::command(std::size_t /*cycle*/, double contour_error) {
  integral_ += h_ * contour_error;
  const double output = gains_.kp * contour_error + gains_.ki * integral_ +
                        gains_.kd * (contour_error - previous_error_);
  previous_error_ = contour_error;
  return output;
}

std::unique_ptr<ContourCompensator> PidCrossCoupling::clone() const {
  return std::make_unique<PidCrossCoupling>(*this);
}

std::string PidCrossCoupling::describe() const {
  std::ostringstream text;
  text << "pidccc(kp=" << gains_.kp << ", ki=" << gains_.ki << ", kd=" << gains_.kd << ")";
  return text.str();
}

}  // namespace netmc::control
