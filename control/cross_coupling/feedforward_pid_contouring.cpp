#include "control/cross_coupling/feedforward_pid_contouring.hpp"

#include <stdexcept>

namespace netmc::control {
namespace {

// Below this speed the reference is at rest (as the estimators' own fallback).
constexpr double kAtRestSpeedMS = 1e-12;

}  // namespace

FeedforwardPidContouring::FeedforwardPidContouring(const FeedforwardPidGains& x_axis,
                                                   const FeedforwardPidGains& y_axis, double sample_period_s,
                                                   std::unique_ptr<ContourErrorEstimator> estimator,
                                                   std::unique_ptr<ContourCompensator> compensator)
    : axes_{FeedforwardPidAxis(x_axis, sample_period_s), FeedforwardPidAxis(y_axis, sample_period_s)},
      estimator_(std::move(estimator)),
      compensator_(std::move(compensator)) {
  if (!estimator_ || !compensator_) {
    throw std::invalid_argument("feedforward PID contouring: the estimator and the compensator must be given");
  }
}

void FeedforwardPidContouring::begin_iteration(const Eigen::Vector2d& /*initial_position*/, std::size_t samples) {
  for (auto& axis : axes_) axis.reset();
  compensator_->begin_iteration(samples);
  travelled_ = false;
}

const ReferencePoint& FeedforwardPidContouring::along_path(const ReferencePoint& reference) {
  const double speed = reference.velocity.norm();
  if (speed > kAtRestSpeedMS) {
    at_rest_.velocity = reference.velocity / speed;
    travelled_ = true;
    return reference;
  }
  if (!travelled_) return reference;
  at_rest_.position = reference.position;
  at_rest_.acceleration.setZero();
  at_rest_.time_s = reference.time_s;
  return at_rest_;
}

ContouringCycle FeedforwardPidContouring::step(std::size_t cycle, const ReferencePoint& reference,
                                               const Eigen::Vector2d& measured) {
  ContouringCycle out;
  out.estimate = estimator_->estimate(along_path(reference), measured);
  for (int axis = 0; axis < 2; ++axis) {
    out.axis_command[axis] = axes_[axis].step(reference.position[axis], reference.acceleration[axis], measured[axis]);
  }
  compensator_->observe_coupling(cycle, out.estimate.cx, out.estimate.cy);
  out.coupling_command = compensator_->command(cycle, out.estimate.contour_error);
  // the structure derived from paper 004, eq. 6, with the sign convention of paper 001's eq. 15
  out.command.x() = out.axis_command.x() - out.estimate.cx * out.coupling_command;
  out.command.y() = out.axis_command.y() + out.estimate.cy * out.coupling_command;
  return out;
}

void FeedforwardPidContouring::end_iteration() { compensator_->end_iteration(); }

std::string FeedforwardPidContouring::describe() const {
  return axes_[0].describe() + " x " + axes_[1].describe() + " + " + compensator_->describe() + " [estimator " +
         estimator_->name() + "]";
}

}  // namespace netmc::control
