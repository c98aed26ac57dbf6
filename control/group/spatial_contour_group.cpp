#include "control/group/spatial_contour_group.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace netmc::control {

SpatialContour::SpatialContour(std::shared_ptr<const SpatialCircle> circle, double duration_s)
    : circle_(std::move(circle)), duration_s_(duration_s) {
  if (!circle_) throw std::invalid_argument("trajectory: missing");
  if (!(duration_s > 0.0) || !std::isfinite(duration_s)) {
    throw std::invalid_argument("duration: expected a positive duration");
  }
}

void SpatialContour::sample(double time_s, GroupReference& out) const {
  assign_reference(circle_->sample(time_s), out);
  out.time_s = time_s;
}

double SpatialContour::contour_error(const AxisVector& point, const GroupReference&) const {
  return circle_->distance(Eigen::Vector3d(point[0], point[1], point[2]));
}

SpatialSarcGroupController::SpatialSarcGroupController(const SpatialSarcGains& gains,
                                                       double sample_period_s,
                                                       std::shared_ptr<const SpatialCircle> circle)
    : gains_(gains), controller_(gains, sample_period_s, std::move(circle)) {
  cycle_.command.setZero(3);
  cycle_.axis_command.setZero(3);
}

void SpatialSarcGroupController::begin_iteration(const AxisVector& initial_position, std::size_t) {
  controller_.begin(Eigen::Vector3d(initial_position[0], initial_position[1], initial_position[2]));
}

const GroupCycle& SpatialSarcGroupController::step(std::size_t, const GroupReference& reference,
                                                   const AxisVector& measured) {
  SpatialReferencePoint point;
  point.position = reference.position.head<3>();
  point.velocity = reference.velocity.head<3>();
  point.acceleration = reference.acceleration.head<3>();
  cycle_.command = controller_.step(point, Eigen::Vector3d(measured[0], measured[1], measured[2]));
  cycle_.axis_command = cycle_.command;  // no per-axis loops: the task-space law is the command
  // The controller's view of the contour error: the distance its contour coordinates give.
  cycle_.estimate.contour_error = controller_.task_error().head<2>().norm();
  return cycle_;
}

std::string SpatialSarcGroupController::describe() const {
  const auto& g = gains_;
  const auto number = [](double value) {
    std::ostringstream text;  // %g, as the planar controllers describe their gains
    text << value;
    return text.str();
  };
  return "gtcf-sarc, three axes: Lambda = diag(" + number(g.lambda[0]) + ", " + number(g.lambda[1]) + ", " +
         number(g.lambda[2]) + "), K_s = diag(" + number(g.feedback[0]) + ", " + number(g.feedback[1]) + ", " +
         number(g.feedback[2]) + "), F_M = " + number(g.uncertainty_bound[0]) + " V";
}


}  // namespace netmc::control
