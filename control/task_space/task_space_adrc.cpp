#include "control/task_space/task_space_adrc.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

ExtendedStateObserver make_observer(const GtcfAdrcGains& gains, int coordinate, double h) {
  require_positive(gains.loop_bandwidth[coordinate], "gtcf-adrc loop bandwidth");
  // b0 = 1: the observer's input is the commanded task acceleration.
  return ExtendedStateObserver(gains.observer_bandwidth[coordinate], 1.0, h, gains.discretization);
}

}  // namespace

TaskSpaceAdrc::TaskSpaceAdrc(const GtcfAdrcGains& gains, double sample_period_s,
                             std::shared_ptr<const TaskFrame> frame)
    : gains_(gains),
      frame_(std::move(frame)),
      observers_{make_observer(gains, 0, sample_period_s), make_observer(gains, 1, sample_period_s)} {
  if (!frame_) throw std::invalid_argument("gtcf-adrc: missing task frame");
  for (int i = 0; i < 2; ++i) {
    require_positive(gains.mass[i], "gtcf-adrc mass");
    require_non_negative(gains.damping[i], "gtcf-adrc damping");
    require_non_negative(gains.coulomb[i], "gtcf-adrc coulomb");
  }
  require_non_negative(gains.friction_slope, "gtcf-adrc friction slope");
}

void TaskSpaceAdrc::begin_iteration(const Eigen::Vector2d& initial_position, std::size_t) {
  // The stage starts at rest: r = r(q0), r' = 0, no disturbance estimate yet.
  const TaskCoordinates r = frame_->at(initial_position);
  rm_raw_ = r.rm;
  rm_unwrapped_ = r.rm;
  observers_[0].reset(r.rc);
  observers_[1].reset(r.rm);
  recent_commands_.assign(gains_.observer_input_delay + 1, Eigen::Vector2d::Zero());
}

ContouringCycle TaskSpaceAdrc::step(std::size_t, const ReferencePoint& reference,
                                    const Eigen::Vector2d& q) {
  // Followed along the contour from the previous cycle (a contour that crosses itself would make
  // the global foot point jump between branches).
  const TaskCoordinates actual = frame_->near(q, rm_raw_);
  const TaskCoordinates desired = frame_->near(reference.position, actual.rm);
  const double perimeter = frame_->perimeter_m();
  const auto wrap = [&](double difference) {
    return perimeter > 0.0 ? std::remainder(difference, perimeter) : difference;
  };
  rm_unwrapped_ += wrap(actual.rm - rm_raw_);
  rm_raw_ = actual.rm;

  // Task reference r_d = [0, rm(q_d)] with its analytic derivatives (rm is arc length along the
  // motion): rm_d is placed on the unwrapped axis through the wrapped tangential error.
  const double speed = reference.velocity.norm();
  const double tangential_acceleration =
      speed > 0.0 ? reference.velocity.dot(reference.acceleration) / speed : 0.0;
  const Eigen::Vector2d r_d(0.0, rm_unwrapped_ - wrap(actual.rm - desired.rm));
  const Eigen::Vector2d r_d_rate(0.0, speed);
  const Eigen::Vector2d r_d_acceleration(0.0, tangential_acceleration);

  // paper 001, eq. 10 per task coordinate, b0 = 1, gains in bandwidth form.
  Eigen::Vector2d task_command, task_velocity;
  for (int i = 0; i < 2; ++i) {
    const ExtendedStateObserver& z = observers_[i];
    const double w = gains_.loop_bandwidth[i];
    task_command[i] = r_d_acceleration[i] + w * w * (r_d[i] - z.position()) +
                      2.0 * w * (r_d_rate[i] - z.velocity()) - z.disturbance();
    task_velocity[i] = z.velocity();
  }

  // Back to the axes: u = M0 (q_d'' + J^-1 (u_t - r_d'')) + B0 q' + A0 S_f(q') (header).
  const Eigen::Matrix2d inverse = actual.jacobian.inverse();
  const Eigen::Vector2d velocity = inverse * task_velocity;
  const Eigen::Vector2d acceleration = reference.acceleration + inverse * (task_command - r_d_acceleration);
  ContouringCycle out;
  for (int i = 0; i < 2; ++i) {
    const double friction =
        gains_.coulomb[i] * 2.0 / std::numbers::pi * std::atan(gains_.friction_slope * velocity[i]);
    out.command[i] = gains_.mass[i] * acceleration[i] + gains_.damping[i] * velocity[i] + friction;
  }
  out.axis_command = out.command;
  out.estimate.contour_error = actual.rc;

  // paper 001, eq. 9: advance each observer with the measured coordinate and the task
  // acceleration just commanded (what acts late under delay lands in z3).
  recent_commands_.push_back(task_command);
  recent_commands_.pop_front();
  observers_[0].update(actual.rc, recent_commands_.front()[0]);
  observers_[1].update(rm_unwrapped_, recent_commands_.front()[1]);
  return out;
}

std::string TaskSpaceAdrc::describe() const {
  std::ostringstream text;
  text << "gtcf-adrc(wc=" << gains_.loop_bandwidth[0] << ", wm=" << gains_.loop_bandwidth[1]
       << ", woc=" << gains_.observer_bandwidth[0] << ", wom=" << gains_.observer_bandwidth[1]
       << ", observer="
       << (gains_.discretization == Discretization::forward_euler ? "euler" : "zoh");
  if (gains_.observer_input_delay > 0) text << ", observer input delay=" << gains_.observer_input_delay;
  text << ")";
  return text.str();
}

}  // namespace netmc::control
