#pragma once
// The discontinuous projection of the thesis's adaptation laws (paper 000, eq. 2-59 and 3-12),
// one explicit step: an estimate on a face of its box stops while its rate points outwards,
// otherwise it moves and is clamped into the box.

#include <algorithm>

namespace netmc::control {

inline double projected_step(double estimate, double rate, double lower, double upper, double h) {
  if ((estimate >= upper && rate > 0.0) || (estimate <= lower && rate < 0.0)) return estimate;
  return std::clamp(estimate + h * rate, lower, upper);
}

}  // namespace netmc::control
