#pragma once
// Additive disturbance d(t): d_i(t) of paper 001 eq. 3, d of paper 002 eq. 1, d of the thesis
// (paper 000) eq. 3-1 / 4-1, and the Set3 input step of paper 000 ch. 3. Where it enters is
// documented by each plant (acceleration for SecondOrderAxis, input units for the others).
// t is the plant's time since reset.

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

namespace netmc::plant {

struct Disturbance {  // sum of the enabled parts
  double constant = 0.0;
  double sine_amplitude = 0.0, sine_frequency_hz = 0.0, sine_phase_rad = 0.0;
  // The step is active for t >= step_time_s when step_amplitude != 0.
  double step_amplitude = 0.0, step_time_s = 0.0;
  double value(double t) const;
  bool is_zero() const;  // true when constant, sine_amplitude and step_amplitude are all 0
};

// Throws std::invalid_argument (naming `owner` and the field) unless every field is finite and
// sine_frequency_hz >= 0.
void validate_disturbance(const Disturbance& d, std::string_view owner);

// constant + sine part, i.e. d(t) without the step.
double smooth_part(const Disturbance& d, double t);
// True when the smooth part does not depend on t (no sine, or a sine of frequency 0).
bool smooth_part_is_constant(const Disturbance& d);

// Calls piece(t_start, duration, step_level) for the one or two pieces of [t0, t0 + duration)
// on which the step part is constant (the step switches at step_time_s). The integrators handle
// each piece separately so they never integrate across the discontinuity. A switch within
// 1e-12 (relative) of either end counts as at that end: accumulated time round-off must not
// leave sliver pieces of ~1e-16 s.
template <class Piece>
void for_each_smooth_piece(const Disturbance& d, double t0, double duration, Piece&& piece) {
  const double t1 = t0 + duration;
  const double ts = d.step_time_s;
  const double slack = 1e-12 * std::max(1.0, std::abs(ts));
  if (d.step_amplitude == 0.0 || ts >= t1 - slack) {
    piece(t0, duration, 0.0);
  } else if (ts <= t0 + slack) {
    piece(t0, duration, d.step_amplitude);
  } else {
    piece(t0, ts - t0, 0.0);
    piece(ts, t1 - ts, d.step_amplitude);
  }
}

// Short text for describe(): "none" or the enabled parts followed by `unit`.
std::string describe_disturbance(const Disturbance& d, std::string_view unit);

}  // namespace netmc::plant
