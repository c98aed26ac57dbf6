#include "plant/disturbance.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "netsim/random_stream.hpp"
#include "plant/parameter_checks.hpp"

namespace netmc::plant {

double BandLimitedNoise::value(double t) const {
  if (stddev == 0.0) return 0.0;
  const double amplitude = stddev * std::sqrt(2.0 / kComponents);
  double sum = 0.0;
  for (std::size_t i = 0; i < kComponents; ++i) sum += std::sin(angular_frequency[i] * t + phase[i]);
  return amplitude * sum;
}

BandLimitedNoise make_band_limited_noise(double stddev, double bandwidth_hz, std::uint64_t seed) {
  BandLimitedNoise noise;
  noise.stddev = stddev;
  noise.bandwidth_hz = bandwidth_hz;
  noise.seed = seed;
  netsim::RandomStream random(seed, 0x6e6f697365ULL);  // its own stream: "noise"
  const double slice = 2.0 * std::numbers::pi * bandwidth_hz / BandLimitedNoise::kComponents;
  for (std::size_t i = 0; i < BandLimitedNoise::kComponents; ++i) {
    noise.angular_frequency[i] = slice * (static_cast<double>(i) + random.uniform());
    noise.phase[i] = 2.0 * std::numbers::pi * random.uniform();
  }
  return noise;
}

double Disturbance::value(double t) const {
  double d = smooth_part(*this, t);
  if (step_amplitude != 0.0 && t >= step_time_s && t < step_off_s) d += step_amplitude;
  return d;
}

bool Disturbance::is_zero() const {
  return constant == 0.0 && sine_amplitude == 0.0 && step_amplitude == 0.0 && noise.stddev == 0.0;
}

void validate_disturbance(const Disturbance& d, std::string_view owner) {
  require_finite(owner, "disturbance.constant", d.constant);
  require_finite(owner, "disturbance.sine_amplitude", d.sine_amplitude);
  require_non_negative(owner, "disturbance.sine_frequency_hz", d.sine_frequency_hz);
  require_finite(owner, "disturbance.sine_phase_rad", d.sine_phase_rad);
  require_finite(owner, "disturbance.step_amplitude", d.step_amplitude);
  require_finite(owner, "disturbance.step_time_s", d.step_time_s);
  if (std::isnan(d.step_off_s) || d.step_off_s == -std::numeric_limits<double>::infinity()) {
    require_finite(owner, "disturbance.step_off_s", d.step_off_s);
  }
  if (!(d.step_off_s > d.step_time_s)) {
    std::ostringstream message;
    message << owner << ": disturbance.step_off_s must be after disturbance.step_time_s (got on " << d.step_time_s
            << " s, off " << d.step_off_s << " s)";
    throw std::invalid_argument(message.str());
  }
  require_non_negative(owner, "disturbance.noise.stddev", d.noise.stddev);
  if (d.noise.stddev > 0.0) require_positive(owner, "disturbance.noise.bandwidth_hz", d.noise.bandwidth_hz);
}

Disturbance scaled(Disturbance d, double factor) {
  d.constant *= factor;
  d.sine_amplitude *= factor;
  d.step_amplitude *= factor;
  d.noise.stddev *= factor;
  return d;
}

double smooth_part(const Disturbance& d, double t) {
  double value = d.constant + d.noise.value(t);
  if (d.sine_amplitude != 0.0) {
    value += d.sine_amplitude * std::sin(2.0 * std::numbers::pi * d.sine_frequency_hz * t + d.sine_phase_rad);
  }
  return value;
}

bool smooth_part_is_constant(const Disturbance& d) {
  return d.noise.stddev == 0.0 && (d.sine_amplitude == 0.0 || d.sine_frequency_hz == 0.0);
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
    if (std::isfinite(d.step_off_s)) out << " to " << d.step_off_s << " s";
    sep = " + ";
  }
  if (d.noise.stddev != 0.0) {
    out << sep << "noise sd " << d.noise.stddev << " to " << d.noise.bandwidth_hz << " Hz (seed " << d.noise.seed << ")";
  }
  out << " " << unit;
  return out.str();
}

}  // namespace netmc::plant
