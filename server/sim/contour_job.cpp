#include "server/sim/contour_job.hpp"

#include <cmath>
#include <stdexcept>

#include "control/dead_zone_compensated_group.hpp"
#include "control/planar_contour_group.hpp"
#include "control/single_axis_group.hpp"
#include "control/spatial_contour_group.hpp"

namespace netmc::sim {
namespace {

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument(message);
}

}  // namespace

std::string LinkProfile::describe() const {
  std::string text = delay ? delay->describe() : "none";
  if (loss && loss->mean_loss_rate() > 0.0) text += ", loss " + loss->describe();
  return text;
}

void ContourJob::validate() const {
  const int references = (trajectory != nullptr) + (spatial_circle != nullptr) + (axis_reference != nullptr);
  require(references == 1, references == 0 ? "trajectory: missing" : "trajectory: expected one reference, got several");
  require(!spatial_circle || (std::isfinite(duration_s) && duration_s > 0.0),
          "duration: a circle in space needs a positive run length");
  require(axes.size() == axis_count(), "plant: expected " + std::to_string(axis_count()) + " axes, got " +
                                           std::to_string(axes.size()));
  for (const auto& axis : axes) require(axis != nullptr, "plant: missing axis model");
  require(std::isfinite(sample_period_s) && sample_period_s > 0.0,
          "sample_period: expected a positive duration, got " + std::to_string(sample_period_s));
  require(std::isfinite(duration_s) && duration_s >= 0.0,
          "duration: expected a non-negative duration, got " + std::to_string(duration_s));
  require(iterations >= 1, "iterations: expected a whole number >= 1");
  require(std::isfinite(deadline_s) && deadline_s >= 0.0,
          "deadline: expected a non-negative duration, got " + std::to_string(deadline_s));
  require(std::isfinite(compute_delay_s) && compute_delay_s >= 0.0,
          "compute_delay: expected a non-negative duration, got " +
              std::to_string(compute_delay_s));
  require(command_limit > 0.0, "command_limit: expected a positive number");
  require(divergence_limit_m > 0.0, "divergence_limit: expected a positive length");
  require(uplink.delay && uplink.loss && downlink.delay && downlink.loss,
          "delay: every link needs a delay and a loss model");
  require(!initial_position || (static_cast<std::size_t>(initial_position->size()) == axis_count() &&
                                initial_position->allFinite()),
          "initial_position: expected finite coordinates, one per axis");
  const double run_s = run_length_s();
  require(run_s / sample_period_s <= 1e8,
          "sample_period: too many cycles for the run length (more than 1e8)");
  // The work ceiling of one job: 1e9 simulated cycles (about 15 minutes of one core).
  require(static_cast<double>(iterations) * (run_s / sample_period_s + 1.0) <= 1e9,
          "iterations: iterations x cycles per iteration is more than 1e9, the work ceiling of a job");
}

control::AxisVector ContourJob::start_position() const {
  if (initial_position) return *initial_position;
  if (spatial_circle) return spatial_circle->sample(0.0).position;
  if (axis_reference) return control::AxisVector::Constant(1, axis_reference->sample(0.0).position);
  return trajectory->sample(0.0).position;
}

double ContourJob::evaluation_start() const {
  return resolve_evaluation_start(evaluation_start_s, spatial_circle   ? spatial_circle->period_s()
                                                     : axis_reference ? axis_reference->period_s()
                                                                      : trajectory->period_s());
}

std::shared_ptr<const control::GroupContour> ContourJob::contour() const {
  if (spatial_circle) return std::make_shared<control::SpatialContour>(spatial_circle, duration_s);
  if (axis_reference) return std::make_shared<control::SingleAxisTrack>(axis_reference);
  return std::make_shared<control::PlanarContour>(trajectory);
}

std::unique_ptr<control::GroupController> ContourJob::make_controller() const {
  std::unique_ptr<control::GroupController> out;
  if (spatial_circle) {
    out = control::make_spatial_group_controller(controller_name, controller, sample_period_s, spatial_circle);
  } else if (axis_reference) {
    out = control::make_tracking_group_controller(controller_name, controller, sample_period_s);
  } else {
    out = control::make_planar_group_controller(controller_name, controller, sample_period_s, *trajectory);
  }
  if (controller.dead_zone_inverse.empty()) return out;
  require(controller.dead_zone_inverse.size() == axis_count(),
          "controller.dead_zone_inverse: expected one dead zone per axis of the group");
  return std::make_unique<control::DeadZoneCompensatedGroup>(std::move(out), controller.dead_zone_inverse);
}

double ContourJob::run_length_s() const {
  if (duration_s > 0.0) return duration_s;
  return axis_reference ? axis_reference->duration_s() : trajectory->duration_s();
}

std::size_t ContourJob::cycles() const {
  return static_cast<std::size_t>(std::llround(run_length_s() / sample_period_s)) + 1;
}

}  // namespace netmc::sim
