#include "control/data_driven/compact_form_mfac.hpp"

#include <cmath>
#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {

CompactFormMfacAxis::CompactFormMfacAxis(const CompactFormMfacGains& gains) : gains_(gains) {
  require_positive(gains_.mu, "mfac mu");
  require_positive(gains_.lambda, "mfac lambda");
  require_positive(gains_.rho, "mfac rho");
  require_positive(gains_.eta, "mfac eta");
  require_non_negative(gains_.epsilon, "mfac epsilon");
  require_positive(gains_.phi_initial, "mfac phi_initial");
  require_non_negative(gains_.contour_weight, "mfac delta");
  reset(0.0);
}

void CompactFormMfacAxis::reset(double position) {
  phi_ = gains_.phi_initial;
  previous_position_ = position;
  previous_command_ = 0.0;
  previous_increment_ = 0.0;
}

double CompactFormMfacAxis::command(double position, double, double desired_next, double contour_error) {
  const double du = previous_increment_;
  const double dy = position - previous_position_;
  phi_ += gains_.eta * du * (dy - phi_ * du) / (gains_.mu + du * du);
  if (std::abs(phi_) <= gains_.epsilon || std::abs(du) <= gains_.epsilon || phi_ * gains_.phi_initial < 0.0) {
    phi_ = gains_.phi_initial;
  }
  const double target = desired_next - gains_.contour_weight * contour_error;
  const double increment = gains_.rho * phi_ * (target - position) / (gains_.lambda + phi_ * phi_);
  const double u = previous_command_ + increment;
  previous_position_ = position;
  previous_command_ = u;
  previous_increment_ = increment;
  return u;
}

std::unique_ptr<DataDrivenAxisLaw> CompactFormMfacAxis::clone() const {
  return std::make_unique<CompactFormMfacAxis>(*this);
}

std::string CompactFormMfacAxis::describe() const {
  std::ostringstream out;
  out << "CFDL-MFAC(mu=" << gains_.mu << ", lambda=" << gains_.lambda << ", rho=" << gains_.rho
      << ", eta=" << gains_.eta << ", Phi(1)=" << gains_.phi_initial << ", delta=" << gains_.contour_weight << ")";
  return out.str();
}

}  // namespace netmc::control
