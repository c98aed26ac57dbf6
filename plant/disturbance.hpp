#pragma once
// Additive disturbance d(t): d_i(t) of paper 001 eq. 3, d of paper 002 eq. 1, d of the thesis
// (paper 000) eq. 3-1 / 4-1, the thesis's Set3 input step (on between two times) and band-limited
// noise. Where it enters is documented by each plant (acceleration for SecondOrderAxis, input
// units for the others). t is the plant's time since reset.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

namespace netmc::plant {

// Band-limited noise as a sum of sinusoids, one per equal slice of [0, bandwidth], each at a
// random frequency inside its slice with a random phase; amplitude sqrt(2/N) stddev each, so the
// variance over a long run is stddev^2 and the spectrum is flat up to the bandwidth. Smooth and
// stateless: the integrators take it like the sine, and a run is reproducible from its seed.
struct BandLimitedNoise {
  static constexpr std::size_t kComponents = 32;
  double stddev = 0.0;
  double bandwidth_hz = 0.0;
  std::uint64_t seed = 1;
  std::array<double, kComponents> angular_frequency{};  // rad/s, drawn by make_band_limited_noise
  std::array<double, kComponents> phase{};
  double value(double t) const;
};

// Draws the components (deterministic in `seed`); stddev = 0 gives no noise.
BandLimitedNoise make_band_limited_noise(double stddev, double bandwidth_hz, std::uint64_t seed);

struct Disturbance {  // sum of the enabled parts
  double constant = 0.0;
  double sine_amplitude = 0.0, sine_frequency_hz = 0.0, sine_phase_rad = 0.0;
  // The step is active for step_time_s <= t < step_off_s when step_amplitude != 0.
  double step_amplitude = 0.0, step_time_s = 0.0;
  double step_off_s = std::numeric_limits<double>::infinity();
  BandLimitedNoise noise;
  double value(double t) const;
  bool is_zero() const;  // true when constant, sine, step and noise amplitudes are all 0
};

// Throws std::invalid_argument (naming `owner` and the field) unless every field is finite (the
// step's off time may be +inf), sine_frequency_hz >= 0, step_off_s > step_time_s and the noise
// has stddev >= 0 and, when on, a bandwidth > 0.
void validate_disturbance(const Disturbance& d, std::string_view owner);

// `d` with every amplitude times `factor` (a disturbance in an input unit as an acceleration).
Disturbance scaled(Disturbance d, double factor);

// constant + sine + noise, i.e. d(t) without the step.
double smooth_part(const Disturbance& d, double t);
// True when the smooth part does not depend on t (no noise, and no sine or a sine of frequency 0).
bool smooth_part_is_constant(const Disturbance& d);

// Calls piece(t_start, duration, step_level) for the one to three pieces of [t0, t0 + duration)
// on which the step part is constant (it switches at step_time_s and step_off_s). The integrators
// handle each piece separately so they never integrate across a discontinuity. A switch within
// 1e-12 (relative) of either end counts as at that end: accumulated time round-off must not
// leave sliver pieces of ~1e-16 s.
template <class Piece>
void for_each_smooth_piece(const Disturbance& d, double t0, double duration, Piece&& piece) {
  const double t1 = t0 + duration;
  if (d.step_amplitude == 0.0) {
    piece(t0, duration, 0.0);
    return;
  }
  auto level_at = [&](double t) {
    return t >= d.step_time_s && t < d.step_off_s ? d.step_amplitude : 0.0;
  };
  auto inside = [&](double ts) {
    const double slack = 1e-12 * std::max(1.0, std::abs(ts));
    return ts > t0 + slack && ts < t1 - slack;
  };
  // Switch times strictly inside the interval, in order; the level of each piece is read at its
  // middle so a switch snapped to an end is decided consistently.
  double cuts[2];
  int count = 0;
  if (inside(d.step_time_s)) cuts[count++] = d.step_time_s;
  if (inside(d.step_off_s)) cuts[count++] = d.step_off_s;
  if (count == 0) {  // the held interval as given: no rounding of t0 + duration - t0
    piece(t0, duration, level_at(t0 + 0.5 * duration));
    return;
  }
  double start = t0;
  for (int i = 0; i <= count; ++i) {
    const double end = i < count ? cuts[i] : t1;
    piece(start, end - start, level_at(0.5 * (start + end)));
    start = end;
  }
}

// Short text for describe(): "none" or the enabled parts followed by `unit`.
std::string describe_disturbance(const Disturbance& d, std::string_view unit);

}  // namespace netmc::plant
