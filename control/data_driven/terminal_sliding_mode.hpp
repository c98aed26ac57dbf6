#pragma once
// Paper 002's discrete terminal sliding mode: the sliding variable (eq. 17)
//   s(k) = lambda1 e(k) + lambda2 e(k-1)^alpha - lambda1 (1 - beta) e(k-1)
// with e^alpha = sign(e) |e|^alpha (netmc's assumption [A]), and the reaching law (eq. 18-20)
//   s(k+1) = E1(s) s(k) - E2(s) sgn s(k),  E1 = (1 - qT) / cosh(delta1 s),  E2 = lambda cosh(delta2 s).
// The hyperbolic terms grow like e^|delta s|; their argument is bounded (kMaxHyperbolicArgument)
// so that a large transient error gives a large but finite step instead of inf (an implementation
// bound the paper does not need: its errors stay within a few um).

#include <string>

namespace netmc::control {

struct TerminalSlidingModeGains {
  double lambda1 = 0.3, lambda2 = 0.2;
  double alpha = 5.0 / 7.0;   // ratio of odd integers in (0, 1)
  double beta = 0.75;
  double q = 500.0;           // 1/s, 0 < 1 - qT < 1
  double delta1 = 0.25, delta2 = 0.25;
  double lambda = 0.04;       // reaching gain
};

inline constexpr double kMaxHyperbolicArgument = 20.0;

// sign(e) |e|^alpha
// -1, 0 or +1: the sign of x (0 for 0).
double signum(double x);
double signed_power(double e, double alpha);

class TerminalSlidingMode {
 public:
  // Throws std::invalid_argument naming the gain that breaks the paper's ranges.
  TerminalSlidingMode(const TerminalSlidingModeGains& gains, double sample_period_s);

  double sliding_variable(double error, double previous_error) const;  // eq. 17
  double e1(double s) const;                                           // eq. 19
  double e2(double s) const;                                           // eq. 20
  // The reaching law's target s(k+1) for s(k) (eq. 18).
  double next_sliding_variable(double s) const;
  const TerminalSlidingModeGains& gains() const { return gains_; }
  std::string describe() const;

 private:
  TerminalSlidingModeGains gains_;
  double contraction_;  // 1 - qT
};

}  // namespace netmc::control
