#include "control/task_space/task_space_darc.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "control/estimation/box_projection.hpp"
#include "control/parameter_check.hpp"

namespace netmc::control {

Eigen::Matrix<double, 2, 8> darc_regressor(const Eigen::Vector2d& equivalent_acceleration,
                                           const Eigen::Vector2d& velocity, double friction_slope) {
  Eigen::Matrix<double, 2, 8> phi = Eigen::Matrix<double, 2, 8>::Zero();
  for (int i = 0; i < 2; ++i) {
    phi(i, i) = equivalent_acceleration[i];
    phi(i, 2 + i) = velocity[i];
    phi(i, 4 + i) = 2.0 / std::numbers::pi * std::atan(friction_slope * velocity[i]);
    phi(i, 6 + i) = -1.0;
  }
  return phi;
}

void require_parameter_box(const ParameterVector& initial, const ParameterVector& lower,
                           const ParameterVector& upper, const std::string& controller) {
  for (int i = 0; i < 8; ++i) {
    require_finite(lower[i], controller + " theta_min");
    require_finite(upper[i], controller + " theta_max");
    if (!(lower[i] <= initial[i] && initial[i] <= upper[i])) {
      throw std::invalid_argument(controller + " theta_hat(0): element " + std::to_string(i + 1) +
                                  " must lie within [theta_min, theta_max]");
    }
  }
  // The model needs positive masses (M_t > 0, property P1).
  if (!(lower[0] > 0.0 && lower[1] > 0.0)) {
    throw std::invalid_argument(controller + " theta_min: the masses M1, M2 need positive lower bounds");
  }
}

TaskSpaceDarc::TaskSpaceDarc(const DarcGains& gains, double sample_period_s,
                             std::shared_ptr<const TaskFrame> frame,
                             const InitializationFilterSettings& filter, LocalFrameRate local_rate)
    : gains_(gains),
      h_(require_positive(sample_period_s, "sample period")),
      sliding_(gains.lambda, sample_period_s, std::move(frame), filter, local_rate),
      estimate_(gains.initial_estimate) {
  require_non_negative(gains.friction_slope, "darc friction slope");
  for (int i = 0; i < 2; ++i) require_non_negative(gains.feedback[i], "darc feedback");
  for (int i = 0; i < 8; ++i) require_non_negative(gains.adaptation[i], "darc adaptation");
  require_parameter_box(gains.initial_estimate, gains.lower, gains.upper, "darc");
}

void TaskSpaceDarc::begin_iteration(const Eigen::Vector2d&, std::size_t) {
  sliding_.reset();
  estimate_ = gains_.initial_estimate;
}

ContouringCycle TaskSpaceDarc::step(std::size_t cycle, const ReferencePoint& reference,
                                    const Eigen::Vector2d& q) {
  const SlidingState state = sliding_.update(cycle, reference, q);
  const Eigen::Matrix<double, 2, 8> phi =
      darc_regressor(state.equivalent_acceleration, state.velocity, gains_.friction_slope);

  // u = Phi_c theta_hat - J^T K s (eq. 3-19/3-21 in Cartesian form, u_s = -K s in the task frame)
  ContouringCycle out;
  out.command = phi * estimate_ - state.jacobian.transpose() * gains_.feedback.cwiseProduct(state.s);
  out.axis_command = out.command;
  out.estimate.contour_error = state.error[0];

  // eq. 3-23 tau = Psi^T s = -Phi_c^T J^-1 s; eq. 3-11/3-12 discontinuous projection.
  const ParameterVector tau = -phi.transpose() * (state.inverse * state.s);
  for (int i = 0; i < 8; ++i) {
    estimate_[i] = projected_step(estimate_[i], gains_.adaptation[i] * tau[i], gains_.lower[i], gains_.upper[i], h_);
  }
  return out;
}

std::string TaskSpaceDarc::describe() const {
  std::ostringstream text;
  text << sliding_.frame_name() << "-darc(lambda=" << gains_.lambda.transpose()
       << ", K=" << gains_.feedback.transpose() << ", Gamma=" << gains_.adaptation.transpose()
       << sliding_.filter_description() << ")";
  return text.str();
}

std::vector<EstimateName> parameter_estimate_names() {
  return {{"M1_hat", "V/(m/s^2)"}, {"M2_hat", "V/(m/s^2)"}, {"B1_hat", "V/(m/s)"}, {"B2_hat", "V/(m/s)"},
          {"A1_hat", "V"},         {"A2_hat", "V"},         {"dn1_hat", "V"},        {"dn2_hat", "V"}};
}

std::vector<EstimateName> TaskSpaceDarc::estimate_names() const { return parameter_estimate_names(); }

void TaskSpaceDarc::read_estimates(double* out) const {
  for (int i = 0; i < 8; ++i) out[i] = estimate_[i];
}

}  // namespace netmc::control
