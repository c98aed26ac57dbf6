#pragma once
// Discretization by the bilinear (Tustin) transform s = (2/T)(z - 1)/(z + 1), optionally
// prewarped so the discrete response equals the analog one exactly at one frequency, and a
// filter that runs the result sample by sample.

#include <complex>
#include <vector>

#include "control/frequency/transfer_function.hpp"

namespace netmc::control {

// H(z) = (b0 + b1 z^-1 + ... + bn z^-n) / (a0 + a1 z^-1 + ... + an z^-n), a0 != 0.
struct DiscreteTransferFunction {
  std::vector<double> numerator;    // b0 .. bn
  std::vector<double> denominator;  // a0 .. an
  double sample_period_s = 0.0;

  // The frequency response H(e^{jωT}).
  std::complex<double> at(double omega_rad_s) const;
};

// The bilinear transform of a proper G(s) with sample period T. With prewarp_rad_s = ω_p > 0 it
// uses s = (ω_p / tan(ω_p T/2)) (z - 1)/(z + 1), so H(e^{jω_p T}) = G(jω_p). The result is
// normalized to a0 = 1. Throws std::invalid_argument for an improper G, T not positive and
// finite, ω_p outside [0, π/T), or a pole of G at s = 2/T (it would map to z = ∞).
DiscreteTransferFunction tustin(const TransferFunction& continuous, double sample_period_s,
                                double prewarp_rad_s = 0.0);

// Direct form II transposed: one state per pole, sized at construction; step() does not
// allocate.
class DiscreteFilter {
 public:
  // Throws std::invalid_argument for an empty polynomial, a zero a0 or non-finite coefficients.
  explicit DiscreteFilter(const DiscreteTransferFunction& transfer_function);

  // Takes u(k), returns y(k).
  double step(double input);
  // Back to rest: zero state.
  void reset();

 private:
  std::vector<double> b_;  // numerator / a0, padded to the common length
  std::vector<double> a_;  // denominator / a0 (a_[0] = 1), padded likewise
  std::vector<double> state_;
};

}  // namespace netmc::control
