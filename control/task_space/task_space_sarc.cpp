#include "control/task_space/task_space_sarc.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "control/estimation/box_projection.hpp"
#include "control/parameter_check.hpp"

namespace netmc::control {

TaskSpaceSarc::TaskSpaceSarc(const SarcGains& gains, double sample_period_s,
                             std::shared_ptr<const TaskFrame> frame,
                             const InitializationFilterSettings& filter, LocalFrameRate local_rate)
    : gains_(gains), h_(require_positive(sample_period_s, "sample period")),
      sliding_(gains.lambda, sample_period_s, std::move(frame), filter, local_rate) {
  for (int i = 0; i < 2; ++i) {
    require_positive(gains.mass[i], "sarc mass");
    require_non_negative(gains.damping[i], "sarc damping");
    require_non_negative(gains.coulomb[i], "sarc coulomb");
    require_non_negative(gains.feedback[i], "sarc feedback");
    require_non_negative(gains.adaptation[i], "sarc adaptation");
    require_positive(gains.uncertainty_bound[i], "sarc uncertainty bound");
  }
}

void TaskSpaceSarc::begin_iteration(const Eigen::Vector2d&, std::size_t) {
  sliding_.reset();
  estimate_.setZero();
}

ContouringCycle TaskSpaceSarc::step(std::size_t cycle, const ReferencePoint& reference,
                                    const Eigen::Vector2d& q) {
  const SlidingState state = sliding_.update(cycle, reference, q);

  // eq. 2-54 and 2-56 (as implemented: u_s = -J^T K_s s)
  Eigen::Vector2d friction;
  for (int i = 0; i < 2; ++i) {
    friction[i] = gains_.coulomb[i] * 2.0 / std::numbers::pi * std::atan(gains_.friction_slope * state.velocity[i]);
  }
  ContouringCycle out;
  out.command = gains_.mass.cwiseProduct(state.equivalent_acceleration) + gains_.damping.cwiseProduct(state.velocity) +
                friction + estimate_ - state.jacobian.transpose() * gains_.feedback.cwiseProduct(state.s);
  out.axis_command = out.command;
  out.estimate.contour_error = state.error[0];

  // eq. 2-58/2-59: gradient adaptation with projection onto |F_l,i| <= F_M,i
  const Eigen::Vector2d direction = state.inverse * state.s;
  for (int i = 0; i < 2; ++i) {
    estimate_[i] = projected_step(estimate_[i], -gains_.adaptation[i] * direction[i],
                                  -gains_.uncertainty_bound[i], gains_.uncertainty_bound[i], h_);
  }
  return out;
}

std::string TaskSpaceSarc::describe() const {
  std::ostringstream text;
  text << sliding_.frame_name() << "-sarc(lambda=" << gains_.lambda.transpose()
       << ", Ks=" << gains_.feedback.transpose() << ", Gamma=" << gains_.adaptation.transpose()
       << sliding_.filter_description() << ")";
  return text.str();
}

}  // namespace netmc::control
