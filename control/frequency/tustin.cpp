#include "control/frequency/tustin.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace netmc::control {

std::complex<double> DiscreteTransferFunction::at(double omega_rad_s) const {
  // Horner in z^-1.
  const std::complex<double> z_inverse = std::exp(std::complex<double>(0.0, -omega_rad_s * sample_period_s));
  const auto horner = [z_inverse](const std::vector<double>& p) {
    std::complex<double> value = 0.0;
    for (auto c = p.rbegin(); c != p.rend(); ++c) value = value * z_inverse + *c;
    return value;
  };
  return horner(numerator) / horner(denominator);
}

DiscreteTransferFunction tustin(const TransferFunction& continuous, double sample_period_s, double prewarp_rad_s) {
  if (!(sample_period_s > 0.0) || !std::isfinite(sample_period_s)) {
    throw std::invalid_argument("tustin: the sample period must be positive and finite");
  }
  const double nyquist_rad_s = std::numbers::pi / sample_period_s;
  if (!(prewarp_rad_s >= 0.0) || !(prewarp_rad_s < nyquist_rad_s)) {
    throw std::invalid_argument("tustin: the prewarp frequency must lie in [0, pi/T) = [0, " +
                                std::to_string(nyquist_rad_s) + ") rad/s");
  }
  if (!continuous.is_proper()) {
    throw std::invalid_argument("tustin: G(s) must be proper (numerator degree <= denominator degree), got " +
                                continuous.describe());
  }
  // s = c (z - 1)/(z + 1); prewarping picks c so that tan(ωT/2) c = ω at ω = ω_p.
  const double c = prewarp_rad_s > 0.0 ? prewarp_rad_s / std::tan(0.5 * prewarp_rad_s * sample_period_s)
                                       : 2.0 / sample_period_s;
  const std::size_t order = continuous.denominator().size() - 1;
  std::vector<double> numerator_s(order + 1, 0.0);
  std::copy(continuous.numerator().begin(), continuous.numerator().end(),
            numerator_s.end() - static_cast<std::ptrdiff_t>(continuous.numerator().size()));
  const std::vector<double>& denominator_s = continuous.denominator();

  // Multiplying N(s) and D(s) by (z + 1)^n turns each s^(n-k) into c^(n-k) (z - 1)^(n-k) (z + 1)^k.
  std::vector<std::vector<double>> minus_powers{{1.0}}, plus_powers{{1.0}};
  for (std::size_t k = 1; k <= order; ++k) {
    minus_powers.push_back(polynomial_product(minus_powers.back(), {1.0, -1.0}));
    plus_powers.push_back(polynomial_product(plus_powers.back(), {1.0, 1.0}));
  }
  DiscreteTransferFunction discrete{std::vector<double>(order + 1, 0.0), std::vector<double>(order + 1, 0.0),
                                    sample_period_s};
  for (std::size_t k = 0; k <= order; ++k) {
    const std::size_t power = order - k;
    const std::vector<double> basis = polynomial_product(minus_powers[power], plus_powers[k]);
    const double scale = std::pow(c, static_cast<double>(power));
    for (std::size_t i = 0; i <= order; ++i) {
      discrete.numerator[i] += numerator_s[k] * scale * basis[i];
      discrete.denominator[i] += denominator_s[k] * scale * basis[i];
    }
  }
  // a0 = D(c): zero when G has a pole at s = c, which the transform sends to z = ∞.
  double largest = 0.0;
  for (const double a : discrete.denominator) largest = std::max(largest, std::abs(a));
  const double leading = discrete.denominator.front();
  if (std::abs(leading) <= 1e-14 * largest) {
    throw std::invalid_argument("tustin: G(s) has a pole at s = 2/T (or the prewarped equivalent), "
                                "which maps to z = infinity; choose another sample period");
  }
  for (double& b : discrete.numerator) b /= leading;
  for (double& a : discrete.denominator) a /= leading;
  return discrete;
}

DiscreteFilter::DiscreteFilter(const DiscreteTransferFunction& transfer_function) {
  const auto& b = transfer_function.numerator;
  const auto& a = transfer_function.denominator;
  if (b.empty() || a.empty()) throw std::invalid_argument("discrete filter: empty numerator or denominator");
  if (a.front() == 0.0 || !std::isfinite(a.front())) {
    throw std::invalid_argument("discrete filter: the denominator's first coefficient a0 must be nonzero");
  }
  const std::size_t length = std::max(b.size(), a.size());
  b_.assign(length, 0.0);
  a_.assign(length, 0.0);
  for (std::size_t i = 0; i < b.size(); ++i) b_[i] = b[i] / a.front();
  for (std::size_t i = 0; i < a.size(); ++i) a_[i] = a[i] / a.front();
  for (std::size_t i = 0; i < length; ++i) {
    if (!std::isfinite(b_[i]) || !std::isfinite(a_[i])) {
      throw std::invalid_argument("discrete filter: non-finite coefficient");
    }
  }
  state_.assign(length - 1, 0.0);
}

double DiscreteFilter::step(double input) {
  const double output = b_[0] * input + (state_.empty() ? 0.0 : state_[0]);
  const std::size_t n = state_.size();
  for (std::size_t i = 0; i + 1 < n; ++i) state_[i] = state_[i + 1] + b_[i + 1] * input - a_[i + 1] * output;
  if (n > 0) state_[n - 1] = b_[n] * input - a_[n] * output;
  return output;
}

void DiscreteFilter::reset() { std::fill(state_.begin(), state_.end(), 0.0); }

}  // namespace netmc::control
