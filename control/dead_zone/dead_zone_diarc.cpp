#include "control/dead_zone/dead_zone_diarc.hpp"

#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {

void DeadZoneDiarcGains::validate() const {
  loop.validate();
  require_initial_estimate_in_box(initial_estimate, lower, upper, "controller");
  // Assumption 5.3: the box keeps the slopes positive and the products of their signs, so every
  // inverse built from it is well defined.
  if (!(lower[2] > 0.0 && lower[4] > 0.0 && lower[3] >= 0.0 && upper[5] <= 0.0)) {
    throw std::invalid_argument(
        "controller.lower: expected m_r, m_l > 0, m_r b_r >= 0 and m_l b_l <= 0 over the whole box");
  }
  require_positive(initial_covariance, "controller.initial_covariance");
  require_non_negative(forgetting, "controller.forgetting");
  require_non_negative(normalization, "controller.normalization");
  require_positive(covariance_limit, "controller.covariance_limit");
  require_non_negative(estimation_threshold, "controller.estimation_threshold");
  if (gate_margin_samples < 0 || gate_margin_samples > 10000) {
    std::ostringstream text;
    text << "controller.gate_margin_samples: expected an integer in [0, 10000], got " << gate_margin_samples;
    throw std::invalid_argument(text.str());
  }
  require_positive(filter_cutoff_hz, "controller.filter_cutoff_hz");
  require_positive(filter_damping, "controller.filter_damping");
}

DeadZoneDiarc::Estimator::Settings DeadZoneDiarc::estimator_settings(const DeadZoneDiarcGains& gains) {
  gains.validate();
  return least_squares_settings<Estimator>(gains);
}

DeadZoneDiarc::DeadZoneDiarc(const DeadZoneDiarcGains& gains, double sample_period_s)
    : gains_(gains),
      loop_(gains.loop, sample_period_s),
      estimator_(estimator_settings(gains)),
      history_(static_cast<std::size_t>(gains.gate_margin_samples) + 1),
      output_filter_(gains.filter_cutoff_hz, gains.filter_damping, sample_period_s) {
  for (int i = 0; i < 6; ++i) {
    regressor_filters_.emplace_back(gains.filter_cutoff_hz, gains.filter_damping, sample_period_s);
  }
  begin_iteration(0.0, 0);
}

void DeadZoneDiarc::begin_iteration(double initial_position_m, std::size_t) {
  loop_.begin(initial_position_m);
  estimator_.reset();
  inverse_.reset();
  for (auto& f : regressor_filters_) f.reset();
  output_filter_.reset();
  command_[0] = command_[1] = 0.0;
  case_[0] = case_[1] = 0;
  for (auto& sample : history_) sample = {};
  newest_ = 0;
  run_ = 0;
}

void DeadZoneDiarc::estimate_parameters() {
  // thesis (5-34)..(5-36) at the centred instant: both held commands in the same linear piece,
  // and (gate margin) the same piece for `margin` samples before and after.
  const RegressionSample& r = loop_.regression();
  const int piece = case_[0] == case_[1] ? case_[0] : 0;
  run_ = piece != 0 && piece == history_[newest_].piece ? run_ + 1 : (piece != 0 ? 1 : 0);
  newest_ = (newest_ + 1) % history_.size();
  history_[newest_] = {r.velocity, friction_sign(r.velocity, gains_.loop.friction_slope),
                       0.5 * (command_[0] + command_[1]),  // each held for half the span
                       r.acceleration, piece};
  const std::size_t margin = history_.size() - 1;
  const RawSample& sample = history_[(newest_ + 1) % history_.size()];  // `margin` cycles old
  const int gated = run_ >= static_cast<long>(2 * margin + 1) ? sample.piece : 0;
  const double chi = gated != 0 ? 1.0 : 0.0;
  const double right = gated > 0 ? 1.0 : 0.0, left = gated < 0 ? 1.0 : 0.0;
  const double entries[6] = {-chi * sample.velocity, -chi * sample.friction, right * sample.command, -right,
                             left * sample.command,  -left};
  Eigen::Matrix<double, 1, 6> regressor;  // F_f^T, (5-39)
  for (int i = 0; i < 6; ++i) {
    auto& filter = regressor_filters_[static_cast<std::size_t>(i)];
    filter.step(entries[i]);
    regressor[i] = filter.value();
  }
  output_filter_.step(chi * sample.acceleration);
  estimator_.update(regressor, Eigen::Matrix<double, 1, 1>(output_filter_.value()),
                    loop_.sample_period());  // (5-40), (5-41)
}

double DeadZoneDiarc::step(std::size_t, const AxisReference& reference, double measured_m) {
  const DiarcLoopState& st = loop_.measure(reference, measured_m);
  estimate_parameters();
  const DeadZoneTheta& theta = estimator_.estimate();
  // (5-22): w_da1 = x_d'' - lambda x~' - sum a_i^ Y_i with Y = [-x', -S_f(x')].
  const double demand = st.demand_without_model + theta[0] * st.velocity + theta[1] * st.friction;
  const double command = inverse_.invert(demand, {theta[2], theta[3], theta[4], theta[5]});  // (5-4)
  const double threshold = gains_.estimation_threshold;
  command_[1] = command_[0];
  case_[1] = case_[0];
  command_[0] = command;
  case_[0] = demand - threshold > 0.0 ? 1 : (demand + threshold < 0.0 ? -1 : 0);  // (5-34)
  loop_.adapt_disturbance();
  return command;
}

std::string DeadZoneDiarc::describe() const {
  const DiarcLoopGains& g = gains_.loop;
  std::ostringstream text;
  text << "axis-diarc-dead-zone(lambda=" << g.lambda << ", k_s=" << g.feedback << ", gamma=" << g.disturbance_adaptation
       << ", d_cM=" << g.disturbance_bound << ", Gamma0=" << gains_.initial_covariance
       << ", alpha=" << gains_.forgetting << ", H=" << gains_.estimation_threshold
       << ", H_f=" << gains_.filter_cutoff_hz << " Hz, gate margin=" << gains_.gate_margin_samples << ")";
  return text.str();
}

std::vector<EstimateName> DeadZoneDiarc::estimate_names() const {
  return {{"B_hat", "1/s"},          {"A_hat", "m/s^2"},   {"mr_hat", "m/s^2/V"}, {"mrbr_hat", "m/s^2"},
          {"ml_hat", "m/s^2/V"},     {"mlbl_hat", "m/s^2"}, {"dc_hat", "m/s^2"}};
}

void DeadZoneDiarc::read_estimates(double* out) const {
  for (int i = 0; i < 6; ++i) out[i] = estimator_.estimate()[i];
  out[6] = loop_.disturbance_estimate();
}

}  // namespace netmc::control
