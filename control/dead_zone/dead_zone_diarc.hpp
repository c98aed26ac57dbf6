#pragma once
// The thesis's DIARC with dead-zone estimation (paper 000, ch. 5, controller C3 of section 5.4):
// the DIARC law (5-22) on x'' = -B x' - A S_f(x') + D(v), the dead zone's slopes carrying E,
// the adaptive inverse (5-4) built from the estimates, and
// theta = [B, A, m_r, m_r b_r, m_l, m_l b_l] from the indicator-gated least squares
// (5-34)..(5-41): the model is linear in theta only where the dead zone is, so a sample enters
// only when the demand was beyond +-H (Lemma 5.2: then v is outside the gap):
//   F^T = [chi Y_1, chi Y_2, chi_+ v, -chi_+, chi_- v, -chi_-],  y = chi x'',
//   Y_1 = -x', Y_2 = -S_f(x'), chi_+ = [w_d > H], chi_- = [w_d < -H], chi = chi_+ + chi_-,
// both sides through the same H_f (5-39), so y_f = F_f^T theta holds exactly in each case.
// [A] assumed (the thesis is silent): H_f second order (damping 0.7, 50 Hz; chapter 3's form),
// upsilon = 0.1 (chapter 3's), rho_M = 5000 on the whole Gamma. One estimator for both cases
// (the parameters B, A are shared and Gamma(0) = 1000 I_6 is given for all six).
// [A] gate margin: a sample enters only when the same case held for `gate_margin_samples` on
// either side of it (the estimator lags by that much). w_d carries the encoder's quantisation
// through k_s s (one 2.5 mm/s velocity step is 0.5 m/s^2, against H = 2), so the samples next to
// a crossing of +-H are picked by their own noise. Without the margin that selection biases the
// estimates on the quantised loop of section 5.4 (A^ ends on its bound 0.3, C3 worse than C2);
// with 100 samples (20 ms) they end about 0.1 from theta, and unquantised they converge either way.

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

using DeadZoneTheta = Eigen::Matrix<double, 6, 1>;  // [B, A, m_r, m_r b_r, m_l, m_l b_l]

// Thesis section 5.4.1, Exp I.
struct DeadZoneDiarcGains {
  DiarcLoopGains loop;
  DeadZoneTheta initial_estimate = (DeadZoneTheta() << 4.3, 0.9, 3.0, 4.2, 4.0, -3.2).finished();  // theta_N
  DeadZoneTheta lower = (DeadZoneTheta() << 3.0, 0.3, 2.0, 2.5, 2.0, -4.5).finished();  // (5-53)
  DeadZoneTheta upper = (DeadZoneTheta() << 5.5, 1.6, 4.5, 4.5, 4.5, -2.5).finished();
  double initial_covariance = 1000.0;  // Gamma(0) = 1000 I_6
  double forgetting = 0.1;             // alpha (1/s)
  double normalization = 0.1;          // upsilon [A]
  double covariance_limit = 5000.0;    // rho_M [A]
  double estimation_threshold = 2.0;   // H (m/s^2), Lemma 5.2
  int gate_margin_samples = 100;       // [A], see above; 0..10000
  double filter_cutoff_hz = 50.0;      // H_f [A]
  double filter_damping = 0.7;         // H_f [A]
  // Throws std::invalid_argument("controller.<field>: expected ...").
  void validate() const;
};

class DeadZoneDiarc final : public TrackingController {
 public:
  DeadZoneDiarc(const DeadZoneDiarcGains& gains, double sample_period_s);

  void begin_iteration(double initial_position_m, std::size_t samples) override;
  double step(std::size_t cycle, const AxisReference& reference, double measured_m) override;
  std::string describe() const override;
  // B_hat, A_hat, mr_hat, mrbr_hat, ml_hat, mlbl_hat, dc_hat.
  std::vector<EstimateName> estimate_names() const override;
  void read_estimates(double* out) const override;

  const DeadZoneTheta& parameter_estimate() const { return estimator_.estimate(); }
  double disturbance_estimate() const { return loop_.disturbance_estimate(); }

 private:
  using Estimator = ProjectedLeastSquares<6, 1>;
  static Estimator::Settings estimator_settings(const DeadZoneDiarcGains& gains);
  void estimate_parameters();

  DeadZoneDiarcGains gains_;
  DiarcTrackingLoop loop_;
  Estimator estimator_;
  DeadZoneInverse inverse_;
  // Unfiltered, ungated samples of the last gate_margin + 1 cycles (ring), and how many
  // consecutive commands had the present case.
  struct RawSample {
    double velocity = 0.0, friction = 0.0, command = 0.0, acceleration = 0.0;
    int piece = 0;
  };
  std::vector<RawSample> history_;
  std::size_t newest_ = 0;
  long run_ = 0;
  std::vector<SecondOrderLowPass> regressor_filters_;  // F's six entries
  SecondOrderLowPass output_filter_;                   // y = chi x''
  // The last two commands and their cases (+1 right, -1 left, 0 neither), newest first.
  double command_[2] = {0.0, 0.0};
  int case_[2] = {0, 0};
};

}  // namespace netmc::control
