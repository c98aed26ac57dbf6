#pragma once
// The adaptive dead-zone inverse of the thesis (paper 000, eq. 5-4..5-6), in the linear
// parameter form theta_dz = [m_r, m_r b_r, m_l, m_l b_l]:
//   v = (w_d + (m_r b_r)^) / m_r^  on the right (kappa_+ = 1),
//   v = (w_d + (m_l b_l)^) / m_l^  on the left  (kappa_- = 1),
// w_d > 0 picks the right branch, w_d < 0 the left; w_d = 0 the break point nearer to the last
// command v(t^-), so a zero demand does not jump across the gap.

#include <string_view>

namespace netmc::control {

struct DeadZoneEstimate {
  double right_slope = 1.0;     // m_r, > 0
  double right_product = 0.0;   // m_r b_r, >= 0
  double left_slope = 1.0;      // m_l, > 0
  double left_product = 0.0;    // m_l b_l, <= 0
  double right_break() const { return right_product / right_slope; }  // b_r^
  double left_break() const { return left_product / left_slope; }     // b_l^
  // Throws std::invalid_argument("<field>.right_slope: expected ...") unless the signs of
  // assumption 5.2 hold (b_r, b_l = 0 allowed: no gap on that side).
  void validate(std::string_view field) const;
};

class DeadZoneInverse {
 public:
  // Forget v(t^-) (the axis at rest: v = 0).
  void reset() { last_command_ = 0.0; }
  // eq. 5-4 for the demand w_d (the dead zone's desired output) with the estimate `p`; remembers
  // the returned v as the next v(t^-).
  double invert(double demand, const DeadZoneEstimate& p);
  double last_command() const { return last_command_; }

 private:
  double last_command_ = 0.0;
};

}  // namespace netmc::control
