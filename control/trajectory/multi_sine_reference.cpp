#include "control/trajectory/multi_sine_reference.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace netmc::control {
namespace {

void require(bool condition, const char* field, const char* expected) {
  if (condition) return;
  std::string message = "trajectory.multi_sine.";
  message.append(field).append(": expected ").append(expected);
  throw std::invalid_argument(message);
}

}  // namespace

MultiSineParameters thesis_dead_zone_reference(double duration_s) {
  // thesis (5-50); every term starts at its trough, so x_d(0) = 0 with zero velocity.
  MultiSineParameters p;
  p.offset_m = 0.21;
  const double phase = -std::numbers::pi / 2.0;
  p.terms = {{0.08, 0.5, phase}, {0.07, 0.4, phase}, {0.06, 0.6, phase}};
  p.duration_s = duration_s;
  p.period_s = 10.0;  // the least common period of 2 s, 2.5 s and 1.667 s
  return p;
}

MultiSineReference::MultiSineReference(MultiSineParameters parameters) : p_(std::move(parameters)) {
  require(std::isfinite(p_.offset_m), "offset_m", "a finite length");
  require(!p_.terms.empty() && p_.terms.size() <= kMaxTerms, "terms", "1 to 16 sinusoids");
  for (const auto& term : p_.terms) {
    require(std::isfinite(term.amplitude_m), "terms.amplitude_m", "a finite length");
    require(std::isfinite(term.frequency_hz) && term.frequency_hz > 0.0 && term.frequency_hz <= 1e4,
            "terms.frequency_hz", "a frequency in (0, 10 kHz]");
    require(std::isfinite(term.phase_rad), "terms.phase_rad", "a finite angle");
  }
  require(std::isfinite(p_.duration_s) && p_.duration_s > 0.0, "duration_s", "a positive duration");
  require(std::isfinite(p_.period_s) && p_.period_s > 0.0, "period_s", "a positive duration");
}

AxisReference MultiSineReference::sample(double time_s) const {
  AxisReference out;
  out.position = p_.offset_m;
  for (const auto& term : p_.terms) {
    const double w = 2.0 * std::numbers::pi * term.frequency_hz;
    const double angle = w * time_s + term.phase_rad;
    const double s = std::sin(angle);
    const double c = std::cos(angle);
    out.position += term.amplitude_m * s;
    out.velocity += term.amplitude_m * w * c;
    out.acceleration -= term.amplitude_m * w * w * s;
  }
  return out;
}

std::string MultiSineReference::describe() const {
  std::ostringstream text;
  text << "multi-sine(" << p_.offset_m * 1e3 << " mm";
  for (const auto& term : p_.terms) {
    text << " + " << term.amplitude_m * 1e3 << " mm sin(2 pi " << term.frequency_hz << " Hz t";
    if (term.phase_rad != 0.0) text << (term.phase_rad < 0.0 ? " - " : " + ") << std::abs(term.phase_rad);
    text << ")";
  }
  text << ", " << p_.duration_s << " s)";
  return text.str();
}

}  // namespace netmc::control
