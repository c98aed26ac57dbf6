#include "control/data_driven/terminal_sliding_mode.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

double open_unit(double value, std::string_view field) {
  if (!std::isfinite(value) || value <= 0.0 || value >= 1.0) {
    throw std::invalid_argument(std::string(field) + ": expected a number in (0, 1), got " + std::to_string(value));
  }
  return value;
}

double bounded(double x) { return std::clamp(x, -kMaxHyperbolicArgument, kMaxHyperbolicArgument); }

}  // namespace

double signum(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

double signed_power(double e, double alpha) { return signum(e) * std::pow(std::abs(e), alpha); }

TerminalSlidingMode::TerminalSlidingMode(const TerminalSlidingModeGains& gains, double sample_period_s)
    : gains_(gains) {
  require_positive(gains_.lambda1, "dtsmc lambda1");
  require_positive(gains_.lambda2, "dtsmc lambda2");
  open_unit(gains_.alpha, "dtsmc alpha");
  open_unit(gains_.beta, "dtsmc beta");
  require_positive(gains_.q, "dtsmc q");
  require_non_negative(gains_.delta1, "dtsmc delta1");
  require_non_negative(gains_.delta2, "dtsmc delta2");
  require_positive(gains_.lambda, "dtsmc lambda");
  require_positive(sample_period_s, "dtsmc sample period");
  contraction_ = open_unit(1.0 - gains_.q * sample_period_s, "dtsmc 1 - q T");
}

double TerminalSlidingMode::sliding_variable(double error, double previous_error) const {
  return gains_.lambda1 * error + gains_.lambda2 * signed_power(previous_error, gains_.alpha) -
         gains_.lambda1 * (1.0 - gains_.beta) * previous_error;
}

double TerminalSlidingMode::e1(double s) const { return contraction_ / std::cosh(bounded(gains_.delta1 * s)); }

double TerminalSlidingMode::e2(double s) const { return gains_.lambda * std::cosh(bounded(gains_.delta2 * s)); }

double TerminalSlidingMode::next_sliding_variable(double s) const {
  const double contraction = e1(s);
  // The reaching conditions (paper 002, section 5, eq. 65-70) ask |s(k+1)| < |s(k)| without a change of
  // sign beyond the band; cosh(delta2 s) breaks that once |s| is large, so the switching step is
  // bounded by E1 |s|.
  const double step = std::min(e2(s), contraction * std::abs(s) + gains_.lambda);
  return contraction * s - step * signum(s);
}

std::string TerminalSlidingMode::describe() const {
  std::ostringstream out;
  out << "lambda1=" << gains_.lambda1 << ", lambda2=" << gains_.lambda2 << ", alpha=" << gains_.alpha
      << ", beta=" << gains_.beta << ", q=" << gains_.q << ", delta1=" << gains_.delta1
      << ", delta2=" << gains_.delta2 << ", lambda=" << gains_.lambda;
  return out.str();
}

}  // namespace netmc::control
