#include "control/task_space/task_space_diarc.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "control/task_space/box_projection.hpp"
#include "control/parameter_check.hpp"

namespace netmc::control {

SecondOrderLowPass::SecondOrderLowPass(double cutoff_hz, double damping, double h) {
  const double w = 2.0 * std::numbers::pi * require_positive(cutoff_hz, "diarc filter cut-off");
  require_positive(damping, "diarc filter damping");
  Eigen::Matrix2d a;
  a << 0.0, 1.0, -w * w, -2.0 * damping * w;
  const Eigen::Matrix2d left = (Eigen::Matrix2d::Identity() - 0.5 * h * a).inverse();
  propagate_ = left * (Eigen::Matrix2d::Identity() + 0.5 * h * a);
  drive_ = left * Eigen::Vector2d(0.0, w * w) * (0.5 * h);
}

void SecondOrderLowPass::step(double input) {
  state_ = propagate_ * state_ + drive_ * (previous_input_ + input);
  previous_input_ = input;
}

TaskSpaceDiarc::TaskSpaceDiarc(const DiarcGains& gains, double sample_period_s,
                               std::shared_ptr<const TaskFrame> frame,
                               const InitializationFilterSettings& filter, LocalFrameRate local_rate)
    : gains_(gains),
      h_(require_positive(sample_period_s, "sample period")),
      sliding_(gains.lambda, sample_period_s, std::move(frame), filter, local_rate) {
  require_non_negative(gains.forgetting, "diarc forgetting");
  require_non_negative(gains.normalization, "diarc normalization");
  require_positive(gains.covariance_limit, "diarc covariance limit");
  for (int i = 0; i < 2; ++i) {
    require_non_negative(gains.feedback[i], "diarc feedback");
    require_positive(gains.disturbance_bound[i], "diarc disturbance bound");
    require_non_negative(gains.disturbance_adaptation[i], "diarc disturbance adaptation");
    for (auto* filters : {&velocity_filter_, &friction_filter_, &unit_filter_, &command_filter_}) {
      filters->emplace_back(gains.filter_cutoff_hz[i], gains.filter_damping, sample_period_s);
    }
  }
  for (int i = 0; i < 8; ++i) require_positive(gains.initial_covariance[i], "diarc initial covariance");
  require_parameter_box(gains.initial_estimate, gains.lower, gains.upper, "diarc");
  begin_iteration(Eigen::Vector2d::Zero(), 0);
}

void TaskSpaceDiarc::begin_iteration(const Eigen::Vector2d&, std::size_t) {
  sliding_.reset();
  estimate_ = gains_.initial_estimate;
  covariance_ = gains_.initial_covariance.asDiagonal();
  disturbance_.setZero();
  last_command_.setZero();
  for (auto* filters : {&velocity_filter_, &friction_filter_, &unit_filter_, &command_filter_}) {
    for (auto& f : *filters) f.reset();
  }
}

void TaskSpaceDiarc::estimate_parameters(const Eigen::Vector2d& velocity) {
  // eq. 3-38..3-42 on the filtered model, up to the present sample.
  Eigen::Matrix<double, 2, 8> regressor = Eigen::Matrix<double, 2, 8>::Zero();  // Upsilon_f^T
  Eigen::Vector2d filtered_command;
  for (int i = 0; i < 2; ++i) {
    const auto axis = static_cast<std::size_t>(i);
    velocity_filter_[axis].step(velocity[i]);
    friction_filter_[axis].step(2.0 / std::numbers::pi * std::atan(gains_.friction_slope * velocity[i]));
    unit_filter_[axis].step(1.0);
    command_filter_[axis].step(last_command_[i]);  // held over the last period
    regressor(i, i) = velocity_filter_[axis].derivative();
    regressor(i, 2 + i) = velocity_filter_[axis].value();
    regressor(i, 4 + i) = friction_filter_[axis].value();
    regressor(i, 6 + i) = -unit_filter_[axis].value();
    filtered_command[i] = command_filter_[axis].value();
  }
  const Eigen::Vector2d prediction_error = regressor * estimate_ - filtered_command;
  const double normalizer =
      1.0 + gains_.normalization * (regressor * covariance_ * regressor.transpose()).trace();
  const ParameterVector tau = -regressor.transpose() * prediction_error / normalizer;
  const ParameterVector rate = covariance_ * tau;
  for (int i = 0; i < 8; ++i) {
    // Box projection for a non-diagonal Gamma: clamp after the step (digest 2.12 [A]).
    estimate_[i] = projected_step(estimate_[i], rate[i], gains_.lower[i], gains_.upper[i], h_);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> physical(covariance_.topLeftCorner<6, 6>(),
                                                                             Eigen::EigenvaluesOnly);
  if (physical.eigenvalues().maxCoeff() <= gains_.covariance_limit) {
    const Eigen::Matrix<double, 8, 2> gain = covariance_ * regressor.transpose();
    covariance_ += h_ * (gains_.forgetting * covariance_ - gain * gain.transpose() / normalizer);
    covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
  }
}

ContouringCycle TaskSpaceDiarc::step(std::size_t cycle, const ReferencePoint& reference,
                                     const Eigen::Vector2d& q) {
  const SlidingState state = sliding_.update(cycle, reference, q);
  estimate_parameters(state.velocity);
  const Eigen::Matrix<double, 2, 8> phi =
      darc_regressor(state.equivalent_acceleration, state.velocity, gains_.friction_slope);

  ContouringCycle out;
  out.command = phi * estimate_ - disturbance_ - state.jacobian.transpose() * gains_.feedback.cwiseProduct(state.s);
  out.axis_command = out.command;
  out.estimate.contour_error = state.error[0];
  last_command_ = out.command;

  // eq. 3-35: d_hat_c' = Proj(gamma_d J^T s), J^T read as J^-1 off the contour.
  const Eigen::Vector2d direction = state.inverse * state.s;
  for (int i = 0; i < 2; ++i) {
    disturbance_[i] = projected_step(disturbance_[i], gains_.disturbance_adaptation[i] * direction[i],
                                     -gains_.disturbance_bound[i], gains_.disturbance_bound[i], h_);
  }
  return out;
}

std::string TaskSpaceDiarc::describe() const {
  std::ostringstream text;
  text << sliding_.frame_name() << "-diarc(lambda=" << gains_.lambda.transpose()
       << ", K=" << gains_.feedback.transpose() << ", gamma_d=" << gains_.disturbance_adaptation.transpose()
       << ", kappa=" << gains_.forgetting << ", rho_M=" << gains_.covariance_limit
       << sliding_.filter_description() << ")";
  return text.str();
}

std::vector<EstimateName> TaskSpaceDiarc::estimate_names() const {
  auto names = parameter_estimate_names();
  names.push_back({"dc1_hat", "V"});
  names.push_back({"dc2_hat", "V"});
  return names;
}

void TaskSpaceDiarc::read_estimates(double* out) const {
  for (int i = 0; i < 8; ++i) out[i] = estimate_[i];
  out[8] = disturbance_[0];
  out[9] = disturbance_[1];
}

}  // namespace netmc::control
