#pragma once
// tanh for the smoothed Coulomb friction of the plants (paper 001's axis, netmc's assumption [A]: the sign of
// the velocity smoothed by tanh), evaluated once per RK4 stage. libm's tanh goes through expm1
// and was 40 % of a simulated cycle; one exp does, with a short series near zero where
// 1 - e^(-2|x|) would cancel. Relative error below 1e-14 over the whole line (tested against
// std::tanh), so the simulated plants move as with std::tanh to far below their sensors'
// resolution.

#include <cmath>

namespace netmc::plant {

inline double smooth_sign(double x) {
  const double a = std::abs(x);
  double magnitude;
  if (a < 0.01) {
    // tanh a = a - a^3/3 + 2a^5/15 - 17a^7/315 + ...: the next term is below 2.2e-20 a here.
    const double a2 = a * a;
    magnitude = a * (1.0 + a2 * (-1.0 / 3.0 + a2 * (2.0 / 15.0 - a2 * (17.0 / 315.0))));
  } else if (a < 20.0) {
    const double e = std::exp(-2.0 * a);
    magnitude = (1.0 - e) / (1.0 + e);
  } else {
    magnitude = 1.0;  // 1 - tanh 20 < 1e-17
  }
  return std::copysign(magnitude, x);
}

}  // namespace netmc::plant
