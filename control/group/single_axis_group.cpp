#include "control/group/single_axis_group.hpp"

#include <stdexcept>

namespace netmc::control {

SingleAxisTrack::SingleAxisTrack(std::shared_ptr<const MultiSineReference> reference)
    : reference_(std::move(reference)) {
  if (!reference_) throw std::invalid_argument("trajectory: missing");
}

void SingleAxisTrack::sample(double time_s, GroupReference& out) const {
  const AxisReference point = reference_->sample(time_s);
  out.position.setConstant(1, point.position);
  out.velocity.setConstant(1, point.velocity);
  out.acceleration.setConstant(1, point.acceleration);
  out.time_s = time_s;
}

double SingleAxisTrack::contour_error(const AxisVector& point, const GroupReference& reference) const {
  return point[0] - reference.position[0];  // x~ = x - x_d, thesis (5-20)
}

TrackingGroupController::TrackingGroupController(std::unique_ptr<TrackingController> controller)
    : controller_(std::move(controller)) {
  if (!controller_) throw std::invalid_argument("controller: missing");
  has_estimates_ = !controller_->estimate_names().empty();
  cycle_.command.setZero(1);
  cycle_.axis_command.setZero(1);
}

void TrackingGroupController::begin_iteration(const AxisVector& initial_position, std::size_t samples) {
  controller_->begin_iteration(initial_position[0], samples);
}

const GroupCycle& TrackingGroupController::step(std::size_t cycle, const GroupReference& reference,
                                                const AxisVector& measured) {
  const AxisReference point{reference.position[0], reference.velocity[0], reference.acceleration[0]};
  cycle_.command[0] = controller_->step(cycle, point, measured[0]);
  cycle_.axis_command[0] = cycle_.command[0];
  // The controller's own view of its error: the measured tracking error.
  cycle_.estimate.contour_error = measured[0] - point.position;
  if (has_estimates_) controller_->read_estimates(cycle_.estimates.data());
  return cycle_;
}


}  // namespace netmc::control
