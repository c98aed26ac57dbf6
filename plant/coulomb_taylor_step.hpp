#pragma once
// One step of the fifth-order Taylor method for a second-order axis with smoothed Coulomb
// friction and a held forcing (paper 001, eq. 3 with netmc's assumed friction [A]):
//   x'' = a1 x + a2 x' + w - c tanh(x' / s).
// RK4 evaluates tanh at four stages, one after the other, and each waits for the last: the
// plants' friction was 80 % of a simulated cycle. Here tanh is evaluated once per step and the
// time derivatives of x' up to the fifth follow from it in closed form (the derivatives of tanh
// are polynomials in tanh; chain rule of Faa di Bruno for g(x'(t))), so a step costs one exp and
// a few dozen independent multiplications, with local error O(h^6) against RK4's O(h^5).
// The series converges only while the friction's argument moves little over the step
// (tanh has poles at distance pi/2 from the real line): the step is refused (false) when
// |x''| h / s exceeds kCoulombTaylorReach, and the caller takes RK4 instead.

#include <cmath>

#include "plant/smooth_sign.hpp"

namespace netmc::plant {

// Largest change of the friction's argument x'/s over one step that the series takes. At 0.1
// the first neglected term is ~ (0.1 / (pi / 2))^6 ~ 7e-8 of the friction's share of the
// step's velocity change (tests/plant/coulomb_taylor_step_test.cpp measures the accuracy).
inline constexpr double kCoulombTaylorReach = 0.1;

struct CoulombAxisCoefficients {
  double a1 = 0.0, a2 = 0.0;  // 1/s^2, 1/s
  double w = 0.0;             // held forcing, m/s^2
  double c = 0.0;             // Coulomb level, m/s^2
  double inv_scale = 1.0;     // 1/s, s the velocity scale of the smoothing (m/s)
};

// Advances (x, v) by h; false (state untouched) where the series would not hold.
inline bool coulomb_taylor_step(double& x, double& v, double h, const CoulombAxisCoefficients& k) {
  const double t = smooth_sign(v * k.inv_scale);  // tanh(u), u = v / s
  const double v1 = k.a1 * x + k.a2 * v + k.w - k.c * t;
  if (!(std::abs(v1) * h * k.inv_scale <= kCoulombTaylorReach)) return false;
  // Derivatives of g(v) = -c tanh(v / s) in v, from those of tanh in u:
  // T' = S, T'' = -2 T S, T''' = S (6 T^2 - 2), T'''' = S T (16 - 24 T^2), S = 1 - T^2.
  const double s_ = 1.0 - t * t;
  const double t2 = t * t;
  const double c1 = -k.c * k.inv_scale;
  const double c2 = c1 * k.inv_scale;
  const double c3 = c2 * k.inv_scale;
  const double c4 = c3 * k.inv_scale;
  const double g1 = c1 * s_;
  const double g2 = c2 * (-2.0 * t * s_);
  const double g3 = c3 * s_ * (6.0 * t2 - 2.0);
  const double g4 = c4 * s_ * t * (16.0 - 24.0 * t2);
  // v^(n+1) = a1 v^(n-1) + a2 v^(n) + d^n/dt^n g(v(t)), with v^(0) = v and x' = v.
  const double damping = k.a2 + g1;
  const double v2 = k.a1 * v + damping * v1;
  const double v1sq = v1 * v1;
  const double v3 = k.a1 * v1 + damping * v2 + g2 * v1sq;
  const double v4 = k.a1 * v2 + damping * v3 + 3.0 * g2 * v1 * v2 + g3 * v1sq * v1;
  const double v5 = k.a1 * v3 + damping * v4 + g2 * (4.0 * v1 * v3 + 3.0 * v2 * v2) +
                    6.0 * g3 * v1sq * v2 + g4 * v1sq * v1sq;
  x += h * (v + h / 2.0 * (v1 + h / 3.0 * (v2 + h / 4.0 * (v3 + h / 5.0 * v4))));
  v += h * (v1 + h / 2.0 * (v2 + h / 3.0 * (v3 + h / 4.0 * (v4 + h / 5.0 * v5))));
  return true;
}

}  // namespace netmc::plant
