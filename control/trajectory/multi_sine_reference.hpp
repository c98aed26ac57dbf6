#pragma once
// A single-axis reference made of sinusoids (thesis, paper 000, ch. 5, eq. 5-50):
//   x_d(t) = offset + sum_i a_i sin(w_i t + phi_i),
// with its first two derivatives in closed form. The thesis's experiment is
// x_d = 0.21 + 0.08 sin(pi t - pi/2) + 0.07 sin(0.8 pi t - pi/2) + 0.06 sin(1.2 pi t - pi/2) m,
// which starts at rest at 0 and repeats every 10 s.

#include <string>
#include <vector>

#include "control/trajectory/axis_reference.hpp"

namespace netmc::control {

struct SineTerm {
  double amplitude_m = 0.0;
  double frequency_hz = 0.0;  // > 0
  double phase_rad = 0.0;
};

struct MultiSineParameters {
  double offset_m = 0.0;
  std::vector<SineTerm> terms;
  double duration_s = 0.0;  // > 0: the run length
  double period_s = 0.0;    // > 0: one pass of the repeating reference (the metrics' "period")
};

// The reference of the thesis's chapter 5 experiments (5-50), `duration_s` long.
MultiSineParameters thesis_dead_zone_reference(double duration_s);

class MultiSineReference {
 public:
  // At most kMaxTerms terms. Throws std::invalid_argument ("trajectory.multi_sine.<field>: ...")
  // for a non-finite value, a non-positive frequency, duration or period, or no term.
  explicit MultiSineReference(MultiSineParameters parameters);

  static constexpr std::size_t kMaxTerms = 16;

  AxisReference sample(double time_s) const;
  double duration_s() const { return p_.duration_s; }
  double period_s() const { return p_.period_s; }
  const MultiSineParameters& parameters() const { return p_; }
  std::string describe() const;

 private:
  MultiSineParameters p_;
};

}  // namespace netmc::control
