#include "control/group/planar_contour_group.hpp"

#include <stdexcept>

namespace netmc::control {

PlanarContour::PlanarContour(std::shared_ptr<const ReferenceTrajectory> trajectory)
    : trajectory_(std::move(trajectory)) {
  if (!trajectory_) throw std::invalid_argument("trajectory: missing");
}

void PlanarContour::sample(double time_s, GroupReference& out) const {
  assign_reference(trajectory_->sample(time_s), out);
  out.time_s = time_s;
}

double PlanarContour::contour_error(const AxisVector& point, const GroupReference&) const {
  return trajectory_->contour_error(Eigen::Vector2d(point[0], point[1]));
}

PlanarGroupController::PlanarGroupController(std::unique_ptr<ContourController> controller)
    : controller_(std::move(controller)) {
  if (!controller_) throw std::invalid_argument("controller: missing");
  const std::size_t estimates = controller_->estimate_names().size();
  if (estimates > kMaxControllerEstimates) {
    throw std::invalid_argument("controller: " + std::to_string(estimates) + " internal estimates, at most " +
                                std::to_string(kMaxControllerEstimates) + " are recorded");
  }
  has_estimates_ = estimates > 0;
  cycle_.command.setZero(2);
  cycle_.axis_command.setZero(2);
}

void PlanarGroupController::begin_iteration(const AxisVector& initial_position, std::size_t samples) {
  controller_->begin_iteration(Eigen::Vector2d(initial_position[0], initial_position[1]), samples);
}

const GroupCycle& PlanarGroupController::step(std::size_t cycle, const GroupReference& reference,
                                              const AxisVector& measured) {
  ReferencePoint point;
  point.position = reference.position.head<2>();
  point.velocity = reference.velocity.head<2>();
  point.acceleration = reference.acceleration.head<2>();
  point.time_s = reference.time_s;
  const ContouringCycle out = controller_->step(cycle, point, Eigen::Vector2d(measured[0], measured[1]));
  cycle_.command = out.command;
  cycle_.axis_command = out.axis_command;
  cycle_.coupling_command = out.coupling_command;
  cycle_.estimate = out.estimate;
  if (has_estimates_) controller_->read_estimates(cycle_.estimates.data());
  return cycle_;
}

std::unique_ptr<GroupController> PlanarGroupController::clone() const {
  auto copy = controller_->clone();
  if (!copy) return nullptr;
  return std::make_unique<PlanarGroupController>(std::move(copy));
}

}  // namespace netmc::control
