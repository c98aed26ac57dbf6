#pragma once
// The adaptive variable-structure law of the thesis's reference [116] for a plant behind a
// symmetric dead zone (paper 000, section 5.4, controller C5, eq. 5-55), as the thesis ran it:
//   v = e^ w_d,  w_d = x_d'' - c1 z1' - phi theta_p^ - c2 z2 - z1 - sgn(z2) D^,
//   e^' = -beta w_d z2,  theta_p^' = Gamma phi^T z2,  D^' = mu |z2|,
//   z1 = x~ = x - x_d, z2 = z1' + c1 z1, phi = [-x', -S_f(x')] (so phi theta_p = -B x' - A S_f).
// The dead zone is treated as a slope 1/e plus a bounded remainder that sgn(z2) D^ dominates; D^
// only grows, which is the source of the chattering the thesis reports. Velocity by differencing,
// as for the DIARC; S_f as DiarcLoopGains's (chapter 3's form, [A]); explicit Euler updates.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "control/axis/tracking_controller.hpp"

namespace netmc::control {

struct AdaptiveVariableStructureGains {
  double c1 = 100.0;                 // 1/s
  double c2 = 50.0;                  // 1/s
  double mu = 1000.0;                // D^' = mu |z2|
  double parameter_adaptation = 10.0;  // Gamma = 10 I_2
  double beta = 10.0;
  double initial_inverse_gain = 1.0 / 3.6;  // e^(0) (V per m/s^2)
  Eigen::Vector2d initial_parameters{4.3, 0.9};  // theta_p^(0) = [B, A]
  double friction_slope = 9000.0;    // S_f = 2/pi atan(slope x') [A]
  // Throws std::invalid_argument("controller.<field>: expected ...").
  void validate() const;
};

class AdaptiveVariableStructureController final : public TrackingController {
 public:
  AdaptiveVariableStructureController(const AdaptiveVariableStructureGains& gains, double sample_period_s);

  void begin_iteration(double initial_position_m, std::size_t samples) override;
  double step(std::size_t cycle, const AxisReference& reference, double measured_m) override;
  std::string describe() const override;
  // e_hat, B_hat, A_hat (theta_p), D_hat.
  std::vector<EstimateName> estimate_names() const override;
  void read_estimates(double* out) const override;

 private:
  AdaptiveVariableStructureGains gains_;
  double h_;
  double previous_ = 0.0;  // y_k-1
  double inverse_gain_ = 0.0;
  Eigen::Vector2d parameters_ = Eigen::Vector2d::Zero();
  double bound_ = 0.0;  // D^
};

}  // namespace netmc::control
