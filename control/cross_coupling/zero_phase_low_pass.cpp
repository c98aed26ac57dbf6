#include "control/cross_coupling/zero_phase_low_pass.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "control/parameter_check.hpp"

namespace netmc::control {

ZeroPhaseLowPass::ZeroPhaseLowPass(double cutoff_hz, double sample_period_s)
    : enabled_(require_finite(cutoff_hz, "ilc q-filter cutoff") > 0.0) {
  const double h = require_positive(sample_period_s, "sample period");
  if (enabled_) pole_ = std::exp(-2.0 * std::numbers::pi * cutoff_hz * h);
}

void ZeroPhaseLowPass::apply(std::vector<double>& signal, std::size_t begin, std::size_t end) const {
  end = std::min(end, signal.size());
  if (!enabled_ || begin >= end) return;
  const auto first = signal.begin() + static_cast<std::ptrdiff_t>(begin);
  const auto last = signal.begin() + static_cast<std::ptrdiff_t>(end);
  // Start each pass at the edge value so a constant signal passes unchanged.
  double state = *first;
  for (auto it = first; it != last; ++it) *it = state = pole_ * state + (1.0 - pole_) * *it;
  state = *(last - 1);
  for (auto it = last; it != first;) {
    --it;
    *it = state = pole_ * state + (1.0 - pole_) * *it;
  }
}

}  // namespace netmc::control
