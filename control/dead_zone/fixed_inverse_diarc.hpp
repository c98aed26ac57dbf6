#pragma once
// The thesis's DIARC without dead-zone estimation (paper 000, section 5.4, controllers C1, C2, C4):
// the law (5-22) on the model x'' = -B x' - A S_f(x') + E u + f_N, with theta = [B, A, E, f_N]
// from the least squares (5-40)/(5-41), the motor voltage u = w_d / E^ and the command v from a
// fixed dead-zone inverse (5-4) of u (volts in, volts out):
//   C1 ignores the dead zone (v = u), C2 inverts the nominal dead zone (theta_N's dead-zone part
//   divided by E_N = 3.6), C4 inverts the true one (5-51).
// [A] assumed (the thesis is silent): the estimator takes u, the inverse's intended output, as the
// plant's input, and runs on every sample (no indicator: these controllers assume no gap);
// H_f, upsilon and rho_M as in DeadZoneDiarc; E^ within (5-53)'s m_r box [2, 4.5] m/s^2/V and
// f_N^ within +-d_cM.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "control/axis/tracking_controller.hpp"
#include "control/dead_zone/dead_zone_inverse.hpp"
#include "control/dead_zone/diarc_tracking_loop.hpp"
#include "control/estimation/projected_least_squares.hpp"
#include "control/estimation/second_order_low_pass.hpp"

namespace netmc::control {

using MotorTheta = Eigen::Matrix<double, 4, 1>;  // [B, A, E, f_N]

enum class DeadZoneHandling {
  ignored,          // C1
  nominal_inverse,  // C2
  exact_inverse,    // C4
};

// The dead zone each handling inverts, in volts (slopes V/V, products V).
DeadZoneEstimate thesis_dead_zone_inverse(DeadZoneHandling handling);

struct FixedInverseDiarcGains {
  DiarcLoopGains loop;
  DeadZoneHandling handling = DeadZoneHandling::exact_inverse;
  DeadZoneEstimate inverse = thesis_dead_zone_inverse(DeadZoneHandling::exact_inverse);  // unused by `ignored`
  MotorTheta initial_estimate = (MotorTheta() << 4.3, 0.9, 3.6, 0.0).finished();
  MotorTheta lower = (MotorTheta() << 3.0, 0.3, 2.0, -2.0).finished();  // B, A from (5-53); [A] E, f_N
  MotorTheta upper = (MotorTheta() << 5.5, 1.6, 4.5, 2.0).finished();
  double initial_covariance = 1000.0;  // Gamma(0) = 1000 I_4
  double forgetting = 0.1;             // alpha (1/s)
  double normalization = 0.1;          // upsilon [A]
  double covariance_limit = 5000.0;    // rho_M [A]
  double filter_cutoff_hz = 50.0;      // H_f [A]
  double filter_damping = 0.7;
  // The thesis's C1, C2 or C4: `handling` and its inverse.
  static FixedInverseDiarcGains thesis(DeadZoneHandling handling);
  // Throws std::invalid_argument("controller.<field>: expected ...").
  void validate() const;
};

class FixedInverseDiarc final : public TrackingController {
 public:
  FixedInverseDiarc(const FixedInverseDiarcGains& gains, double sample_period_s);

  void begin_iteration(double initial_position_m, std::size_t samples) override;
  double step(std::size_t cycle, const AxisReference& reference, double measured_m) override;
  std::string describe() const override;
  // B_hat, A_hat, E_hat, fN_hat, dc_hat.
  std::vector<EstimateName> estimate_names() const override;
  void read_estimates(double* out) const override;

  const MotorTheta& parameter_estimate() const { return estimator_.estimate(); }

 private:
  using Estimator = ProjectedLeastSquares<4, 1>;
  static Estimator::Settings estimator_settings(const FixedInverseDiarcGains& gains);
  void estimate_parameters();

  FixedInverseDiarcGains gains_;
  DiarcTrackingLoop loop_;
  Estimator estimator_;
  DeadZoneInverse inverse_;
  std::vector<SecondOrderLowPass> regressor_filters_;  // [-x', -S_f, u, 1]
  SecondOrderLowPass output_filter_;                   // x''
  double voltage_[2] = {0.0, 0.0};                     // u of the last two cycles, newest first
};

}  // namespace netmc::control
