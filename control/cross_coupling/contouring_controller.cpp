#include "control/cross_coupling/contouring_controller.hpp"

#include <stdexcept>

namespace netmc::control {

ContouringController::ContouringController(std::unique_ptr<AxisController> x_axis,
                                           std::unique_ptr<AxisController> y_axis,
                                           std::unique_ptr<ContourErrorEstimator> estimator,
                                           std::unique_ptr<ContourCompensator> compensator)
    : axes_{std::move(x_axis), std::move(y_axis)},
      estimator_(std::move(estimator)),
      compensator_(std::move(compensator)) {
  if (!axes_[0] || !axes_[1] || !estimator_ || !compensator_) {
    throw std::invalid_argument("contouring controller: every part must be given");
  }
}

ContouringController::ContouringController(const ContouringController& other)
    : axes_{other.axes_[0]->clone(), other.axes_[1]->clone()},
      estimator_(other.estimator_->clone()),
      compensator_(other.compensator_->clone()) {}

void ContouringController::begin_iteration(const Eigen::Vector2d& initial_position,
                                           std::size_t samples) {
  for (int axis = 0; axis < 2; ++axis) axes_[axis]->reset(initial_position[axis]);
  compensator_->begin_iteration(samples);
}

ContouringCycle ContouringController::step(std::size_t cycle, const ReferencePoint& reference,
                                           const Eigen::Vector2d& measured) {
  ContouringCycle out;
  out.estimate = estimator_->estimate(reference, measured);
  for (int axis = 0; axis < 2; ++axis) {
    out.axis_command[axis] = axes_[axis]->command(reference.position[axis], measured[axis]);
  }
  compensator_->observe_coupling(cycle, out.estimate.cx, out.estimate.cy);
  out.coupling_command = compensator_->command(cycle, out.estimate.contour_error);
  // paper 001, eq. 15
  out.command.x() = out.axis_command.x() - out.estimate.cx * out.coupling_command;
  out.command.y() = out.axis_command.y() + out.estimate.cy * out.coupling_command;
  for (int axis = 0; axis < 2; ++axis) {
    axes_[axis]->commit(reference.position[axis], measured[axis], out.axis_command[axis],
                        out.command[axis]);
  }
  return out;
}

void ContouringController::end_iteration() { compensator_->end_iteration(); }

std::string ContouringController::describe() const {
  return axes_[0]->describe() + " x " + axes_[1]->describe() + " + " + compensator_->describe() +
         " [estimator " + estimator_->name() + "]";
}

}  // namespace netmc::control
