#include "plant/disturbance.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "plant/parameter_checks.hpp"

namespace netmc::plant {

double Disturbance::value(double t) const {
  double d = smooth_part(*this, t);
  if (step_amplitude != 0.0 && t >= step_time_s) d += step_amplitude;
  return d;
}

bool Disturbance::is_zero() const {
  return constant == 0.0 && sine_amplitude == 0.0 && step_amplitude == 0.0;
}

void validate_disturbance(const Disturbance& d, std::string_view owner) {
  require_finite(owner, "disturbance.constant", d.constant);
  require_finite(owner, "disturbance.sine_amplitude", d.sine_amplitude);
  require_non_negative(owner, "disturbance.sine_frequency_hz", d.sine_frequency_hz);
  require_finite(owner, "disturbance.sine_phase_rad", d.sine_phase_rad);
  require_finite(owner, "disturbance.step_amplitude", d.step_amplitude);
  require_finite(owner, "disturbance.step_time_s", d.step_time_s);
}

double smooth_part(const Disturbance& d, double t) {
  if (d.sine_amplitude == 0.0) return d.constant;
  return d.constant + d.sine_amplitude * std::sin(2.0 * std::numbers::pi * d.sine_frequency_hz * t +
                                                  d.sine_phase_rad);
}

bool smooth_part_is_constant(const Disturbance& d) {
  return d.sine_amplitude == 0.0 || d.sine_frequency_hz == 0.0;
}

std::string describe_disturbance(const Disturbance& d, std::string_view unit) {
  if (d.is_zero()) return "none";
  std::ostringstream out;
  const char* sep = "";
  if (d.constant != 0.0) {
    out << "const " << d.constant;
    sep = " + ";
  }
  if (d.sine_amplitude != 0.0) {
    out << sep << d.sine_amplitude << " sin(2pi " << d.sine_frequency_hz << " Hz t + "
        << d.sine_phase_rad << ")";
    sep = " + ";
  }
  if (d.step_amplitude != 0.0) {
    out << sep << "step " << d.step_amplitude << " from " << d.step_time_s << " s";
  }
  out << " " << unit;
  return out.str();
}

}  // namespace netmc::plant
