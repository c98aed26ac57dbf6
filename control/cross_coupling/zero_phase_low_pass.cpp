#include "control/cross_coupling/zero_phase_low_pass.hpp"

#include <cmath>
#include <numbers>

#include "control/parameter_check.hpp"

namespace netmc::control {

ZeroPhaseLowPass::ZeroPhaseLowPass(double cutoff_hz, double sample_period_s)
    : enabled_(require_finite(cutoff_hz, "ilc q-filter cutoff") > 0.0) {
  const double h = require_positive(sample_period_s, "sample period");
  if (enabled_) pole_ = std::exp(-2.0 * std::numbers::pi * cutoff_hz * h);
}

void ZeroPhaseLowPass::apply(std::vector<double>& signal) const {
  if (!enabled_ || signal.empty()) return;
  // Start each pass at the edge value so a constant signal passes unchanged.
  double state = signal.front();
  for (double& value : signal) value = state = pole_ * state + (1.0 - pole_) * value;
  state = signal.back();
  for (auto it = signal.rbegin(); it != signal.rend(); ++it) {
    *it = state = pole_ * state + (1.0 - pole_) * *it;
  }
}

}  // namespace netmc::control
