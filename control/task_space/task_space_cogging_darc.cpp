#include "control/task_space/task_space_cogging_darc.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "control/parameter_check.hpp"
#include "control/estimation/box_projection.hpp"

namespace netmc::control {

Eigen::Matrix<double, 2, kCoggingParameters> cogging_darc_regressor(const CoggingDarcGains& gains,
                                                                    const Eigen::Vector2d& equivalent_acceleration,
                                                                    const Eigen::Vector2d& velocity,
                                                                    const Eigen::Vector2d& desired_velocity,
                                                                    const Eigen::Vector2d& position) {
  Eigen::Matrix<double, 2, kCoggingParameters> phi = Eigen::Matrix<double, 2, kCoggingParameters>::Zero();
  const double wavenumber = 2.0 * std::numbers::pi / gains.pitch_m;
  for (int i = 0; i < 2; ++i) {
    phi(i, i) = equivalent_acceleration[i];
    phi(i, 2 + i) = velocity[i];
    phi(i, 4 + i) = 2.0 / std::numbers::pi * std::atan(gains.friction_slope * desired_velocity[i]);
    // eq. 4-2: +sin, +cos of each harmonic of this axis's position (the force the model adds).
    const auto& harmonics = i == 0 ? gains.x_harmonics : gains.y_harmonics;
    for (int h = 0; h < kCoggingHarmonicsPerAxis; ++h) {
      const double angle = wavenumber * harmonics[h] * position[i];
      const int column = 6 + 2 * (kCoggingHarmonicsPerAxis * i + h);
      phi(i, column) = std::sin(angle);
      phi(i, column + 1) = std::cos(angle);
    }
    phi(i, kCoggingParameters - 2 + i) = -1.0;
  }
  return phi;
}

TaskSpaceCoggingDarc::TaskSpaceCoggingDarc(const CoggingDarcGains& gains, double sample_period_s,
                                           std::shared_ptr<const TaskFrame> frame,
                                           const InitializationFilterSettings& filter, LocalFrameRate local_rate)
    : gains_(gains),
      h_(require_positive(sample_period_s, "sample period")),
      sliding_(gains.lambda, sample_period_s, std::move(frame), filter, local_rate),
      estimate_(gains.initial_estimate) {
  require_positive(gains.pitch_m, "cogging darc pitch");
  require_non_negative(gains.friction_slope, "cogging darc friction slope");
  for (int i = 0; i < 2; ++i) require_non_negative(gains.feedback[i], "cogging darc feedback");
  for (int i = 0; i < kCoggingParameters; ++i) {
    require_non_negative(gains.adaptation[i], "cogging darc adaptation");
    require_finite(gains.lower[i], "cogging darc theta_min");
    require_finite(gains.upper[i], "cogging darc theta_max");
    if (!(gains.lower[i] <= gains.initial_estimate[i] && gains.initial_estimate[i] <= gains.upper[i])) {
      std::ostringstream message;
      message << "cogging darc theta_hat(0): element " << i + 1 << " must lie within [theta_min, theta_max]";
      throw std::invalid_argument(message.str());
    }
  }
  for (const auto* harmonics : {&gains.x_harmonics, &gains.y_harmonics}) {
    for (const int order : *harmonics) {
      if (order < 1) throw std::invalid_argument("cogging darc harmonics: expected orders >= 1");
    }
  }
  if (!(gains.lower[0] > 0.0 && gains.lower[1] > 0.0)) {
    throw std::invalid_argument("cogging darc theta_min: the masses M1, M2 need positive lower bounds");
  }
}

void TaskSpaceCoggingDarc::begin_iteration(const Eigen::Vector2d&, std::size_t) {
  sliding_.reset();
  estimate_ = gains_.initial_estimate;
}

ContouringCycle TaskSpaceCoggingDarc::step(std::size_t cycle, const ReferencePoint& reference,
                                           const Eigen::Vector2d& q) {
  const SlidingState state = sliding_.update(cycle, reference, q);
  const auto phi = cogging_darc_regressor(gains_, state.equivalent_acceleration, state.velocity, reference.velocity, q);
  // u = Phi_r theta_hat - J^T K s (eq. 4-10..4-20 in Cartesian form)
  ContouringCycle out;
  out.command = phi * estimate_ - state.jacobian.transpose() * gains_.feedback.cwiseProduct(state.s);
  out.axis_command = out.command;
  out.estimate.contour_error = state.error[0];
  // tau = Psi_r^T s = -Phi_r^T J^-1 s, discontinuous projection per element (eq. 3-12).
  const CoggingParameterVector tau = -phi.transpose() * (state.inverse * state.s);
  for (int i = 0; i < kCoggingParameters; ++i) {
    estimate_[i] = projected_step(estimate_[i], gains_.adaptation[i] * tau[i], gains_.lower[i], gains_.upper[i], h_);
  }
  return out;
}

std::string TaskSpaceCoggingDarc::describe() const {
  std::ostringstream text;
  text << sliding_.frame_name() << "-darc-cogging(lambda=" << gains_.lambda.transpose()
       << ", K=" << gains_.feedback.transpose() << ", Gamma=" << gains_.adaptation.transpose()
       << ", P=" << gains_.pitch_m * 1e3 << " mm" << sliding_.filter_description() << ")";
  return text.str();
}

std::vector<EstimateName> TaskSpaceCoggingDarc::estimate_names() const {
  std::vector<EstimateName> names = {{"M1_hat", "V/(m/s^2)"}, {"M2_hat", "V/(m/s^2)"}, {"B1_hat", "V/(m/s)"},
                                     {"B2_hat", "V/(m/s)"},   {"A1_hat", "V"},         {"A2_hat", "V"}};
  for (int axis = 0; axis < 2; ++axis) {
    for (const int order : axis == 0 ? gains_.x_harmonics : gains_.y_harmonics) {
      for (const char part : {'S', 'C'}) {
        std::ostringstream name;  // e.g. Sx1_hat: sine amplitude of X's first harmonic
        name << part << (axis == 0 ? 'x' : 'y') << order << "_hat";
        names.push_back({name.str(), "V"});
      }
    }
  }
  names.push_back({"dN1_hat", "V"});
  names.push_back({"dN2_hat", "V"});
  return names;
}

void TaskSpaceCoggingDarc::read_estimates(double* out) const {
  for (int i = 0; i < kCoggingParameters; ++i) out[i] = estimate_[i];
}

}  // namespace netmc::control
