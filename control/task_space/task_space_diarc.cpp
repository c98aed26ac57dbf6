#include "control/task_space/task_space_diarc.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "control/estimation/box_projection.hpp"
#include "control/parameter_check.hpp"

namespace netmc::control {

TaskSpaceDiarc::TaskSpaceDiarc(const DiarcGains& gains, double sample_period_s,
                               std::shared_ptr<const TaskFrame> frame,
                               const InitializationFilterSettings& filter, LocalFrameRate local_rate)
    : gains_(gains),
      h_(require_positive(sample_period_s, "sample period")),
      sliding_(gains.lambda, sample_period_s, std::move(frame), filter, local_rate),
      estimator_(least_squares_settings<ProjectedLeastSquares<8, 2, 6>>(gains)) {
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
  estimator_.reset();
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
  estimator_.update(regressor, filtered_command, h_);
}

ContouringCycle TaskSpaceDiarc::step(std::size_t cycle, const ReferencePoint& reference,
                                     const Eigen::Vector2d& q) {
  const SlidingState state = sliding_.update(cycle, reference, q);
  estimate_parameters(state.velocity);
  const Eigen::Matrix<double, 2, 8> phi =
      darc_regressor(state.equivalent_acceleration, state.velocity, gains_.friction_slope);

  ContouringCycle out;
  out.command = phi * estimator_.estimate() - disturbance_ -
                state.jacobian.transpose() * gains_.feedback.cwiseProduct(state.s);
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
  for (int i = 0; i < 8; ++i) out[i] = estimator_.estimate()[i];
  out[8] = disturbance_[0];
  out[9] = disturbance_[1];
}

}  // namespace netmc::control
