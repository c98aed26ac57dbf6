#include "control/dead_zone/fixed_inverse_diarc.hpp"

#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

constexpr double kNominalGain = 3.6;  // E_N (m/s^2/V), thesis section 5.4

const char* handling_name(DeadZoneHandling handling) {
  switch (handling) {
    case DeadZoneHandling::ignored:
      return "ignored";
    case DeadZoneHandling::nominal_inverse:
      return "nominal-inverse";
    case DeadZoneHandling::exact_inverse:
      return "exact-inverse";
  }
  return "?";
}

}  // namespace

DeadZoneEstimate thesis_dead_zone_inverse(DeadZoneHandling handling) {
  switch (handling) {
    case DeadZoneHandling::ignored:
      return {1.0, 0.0, 1.0, 0.0};  // identity
    case DeadZoneHandling::nominal_inverse:
      // theta_N = [.., 3, 4.2, 4, -3.2] includes E: b_r = 1.4 V, b_l = -0.8 V.
      return {3.0 / kNominalGain, 4.2 / kNominalGain, 4.0 / kNominalGain, -3.2 / kNominalGain};
    case DeadZoneHandling::exact_inverse:
      return {0.9, 0.9 * 1.2, 1.0, -1.0};  // (5-51)
  }
  return {};
}

FixedInverseDiarcGains FixedInverseDiarcGains::thesis(DeadZoneHandling handling) {
  FixedInverseDiarcGains out;
  out.handling = handling;
  out.inverse = thesis_dead_zone_inverse(handling);
  return out;
}

void FixedInverseDiarcGains::validate() const {
  loop.validate();
  inverse.validate("controller.inverse");
  require_initial_estimate_in_box(initial_estimate, lower, upper, "controller");
  if (!(lower[2] > 0.0)) throw std::invalid_argument("controller.lower: expected E's lower bound > 0");
  require_positive(initial_covariance, "controller.initial_covariance");
  require_non_negative(forgetting, "controller.forgetting");
  require_non_negative(normalization, "controller.normalization");
  require_positive(covariance_limit, "controller.covariance_limit");
  require_positive(filter_cutoff_hz, "controller.filter_cutoff_hz");
  require_positive(filter_damping, "controller.filter_damping");
}

FixedInverseDiarc::Estimator::Settings FixedInverseDiarc::estimator_settings(const FixedInverseDiarcGains& gains) {
  gains.validate();
  return least_squares_settings<Estimator>(gains);
}

FixedInverseDiarc::FixedInverseDiarc(const FixedInverseDiarcGains& gains, double sample_period_s)
    : gains_(gains),
      loop_(gains.loop, sample_period_s),
      estimator_(estimator_settings(gains)),
      output_filter_(gains.filter_cutoff_hz, gains.filter_damping, sample_period_s) {
  for (int i = 0; i < 4; ++i) {
    regressor_filters_.emplace_back(gains.filter_cutoff_hz, gains.filter_damping, sample_period_s);
  }
  begin_iteration(0.0, 0);
}

void FixedInverseDiarc::begin_iteration(double initial_position_m, std::size_t) {
  loop_.begin(initial_position_m);
  estimator_.reset();
  inverse_.reset();
  for (auto& f : regressor_filters_) f.reset();
  output_filter_.reset();
  voltage_[0] = voltage_[1] = 0.0;
}

void FixedInverseDiarc::estimate_parameters() {
  // x'' = [-x', -S_f, u, 1] theta at the centred instant (see DiarcTrackingLoop).
  const RegressionSample& r = loop_.regression();
  const double entries[4] = {-r.velocity, -friction_sign(r.velocity, gains_.loop.friction_slope),
                             0.5 * (voltage_[0] + voltage_[1]), 1.0};
  Eigen::Matrix<double, 1, 4> regressor;
  for (int i = 0; i < 4; ++i) {
    auto& filter = regressor_filters_[static_cast<std::size_t>(i)];
    filter.step(entries[i]);
    regressor[i] = filter.value();
  }
  output_filter_.step(r.acceleration);
  estimator_.update(regressor, Eigen::Matrix<double, 1, 1>(output_filter_.value()), loop_.sample_period());
}

double FixedInverseDiarc::step(std::size_t, const AxisReference& reference, double measured_m) {
  const DiarcLoopState& st = loop_.measure(reference, measured_m);
  estimate_parameters();
  const MotorTheta& theta = estimator_.estimate();
  // (5-22) in acceleration, then through E^: u is the motor voltage the law wants.
  const double demand = st.demand_without_model + theta[0] * st.velocity + theta[1] * st.friction - theta[3];
  const double voltage = demand / theta[2];
  const double command =
      gains_.handling == DeadZoneHandling::ignored ? voltage : inverse_.invert(voltage, gains_.inverse);  // (5-4)
  voltage_[1] = voltage_[0];
  voltage_[0] = voltage;
  loop_.adapt_disturbance();
  return command;
}

std::string FixedInverseDiarc::describe() const {
  const DiarcLoopGains& g = gains_.loop;
  std::ostringstream text;
  text << "axis-diarc(dead zone " << handling_name(gains_.handling) << ", lambda=" << g.lambda << ", k_s=" << g.feedback
       << ", gamma=" << g.disturbance_adaptation << ", d_cM=" << g.disturbance_bound
       << ", Gamma0=" << gains_.initial_covariance << ", alpha=" << gains_.forgetting << ")";
  return text.str();
}

std::vector<EstimateName> FixedInverseDiarc::estimate_names() const {
  return {{"B_hat", "1/s"}, {"A_hat", "m/s^2"}, {"E_hat", "m/s^2/V"}, {"fN_hat", "m/s^2"}, {"dc_hat", "m/s^2"}};
}

void FixedInverseDiarc::read_estimates(double* out) const {
  for (int i = 0; i < 4; ++i) out[i] = estimator_.estimate()[i];
  out[4] = loop_.disturbance_estimate();
}

}  // namespace netmc::control
