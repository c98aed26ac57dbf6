#pragma once
// The part of the thesis's single-axis DIARC (paper 000, eq. 5-19..5-25, n = 2) that does not
// depend on how the model and the dead zone are handled, shared by the controllers C1..C4:
//   x' by differencing the measured position (the thesis's experiment: 0.5 um at T_s = 0.2 ms),
//   s = x~' + lambda x~ (5-19), x~ = x - x_d,
//   w_d = x_d'' - lambda x~' - sum a_i^ Y_i - d_c^ - k_s s (5-22), the model term added by the caller,
//   d_c^' = Proj(gamma s) within |d_c^| <= d_cM (5-25),
// and the regression sample of the estimators, centred one period back so that the second
// difference of positions, the velocity and the held commands describe the same instant.

#include <cmath>
#include <cstddef>
#include <numbers>

#include "control/axis/tracking_controller.hpp"

namespace netmc::control {

// Thesis section 5.4.1: one gain set for C1..C4.
struct DiarcLoopGains {
  double lambda = 200.0;                  // lambda (1/s), s = x~' + lambda x~
  double feedback = 200.0;                // k_s = k_s1 + k_s2 (1/s), w_ds = -k_s s
  double disturbance_adaptation = 1000.0; // gamma (1/s^2), d_c^' = gamma s
  double disturbance_bound = 2.0;         // d_cM (m/s^2)
  // S_f(x') = 2/pi atan(friction_slope x'): chapter 5 gives no S_f; [A] assumed chapter 3's.
  double friction_slope = 9000.0;         // s/m
  // Throws std::invalid_argument("controller.<field>: expected ...").
  void validate() const;
};

// The smooth Coulomb sign of the controllers' model.
inline double friction_sign(double velocity, double slope) {
  return 2.0 / std::numbers::pi * std::atan(slope * velocity);
}

struct DiarcLoopState {
  double velocity = 0.0;        // x' (m/s), differenced
  double error = 0.0;           // x~ (m)
  double velocity_error = 0.0;  // x~' (m/s)
  double s = 0.0;               // (m/s)
  double friction = 0.0;        // S_f(x')
  // x_d'' - lambda x~' - d_c^ - k_s s (m/s^2): w_d without the model term.
  double demand_without_model = 0.0;
};

// One regression instant, one period before the present sample.
struct RegressionSample {
  double acceleration = 0.0;  // (y_k - 2 y_k-1 + y_k-2) / T_s^2
  double velocity = 0.0;      // (y_k - y_k-2) / (2 T_s)
};

class DiarcTrackingLoop {
 public:
  DiarcTrackingLoop(const DiarcLoopGains& gains, double sample_period_s);

  void begin(double initial_position_m);
  // The present sample: updates the velocity, s and the regression sample.
  const DiarcLoopState& measure(const AxisReference& reference, double measured_m);
  // (5-25) with the present s; call once per cycle after the command is formed.
  void adapt_disturbance();

  const DiarcLoopState& state() const { return state_; }
  const RegressionSample& regression() const { return regression_; }
  double disturbance_estimate() const { return disturbance_; }
  const DiarcLoopGains& gains() const { return gains_; }
  double sample_period() const { return h_; }

 private:
  DiarcLoopGains gains_;
  double h_;
  double previous_ = 0.0, before_previous_ = 0.0;  // y_k-1, y_k-2
  double disturbance_ = 0.0;                        // d_c^
  DiarcLoopState state_;
  RegressionSample regression_;
};

}  // namespace netmc::control
