#include "server/sim/contour_job.hpp"

#include <cmath>
#include <stdexcept>

#include "control/group/dead_zone_compensated_group.hpp"
#include "control/trajectory/multi_sine_reference.hpp"
#include "control/group/planar_contour_group.hpp"
#include "control/group/single_axis_group.hpp"
#include "control/group/spatial_contour_group.hpp"

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

std::size_t reference_dimension(const JobReference& reference) {
  return std::visit(
      [](const auto& kind) -> std::size_t {
        using Kind = std::decay_t<decltype(kind)>;
        if constexpr (std::is_same_v<Kind, std::shared_ptr<const control::SpatialCircle>>) return 3;
        if constexpr (std::is_same_v<Kind, std::shared_ptr<const control::MultiSineReference>>) return 1;
        return 2;
      },
      reference);
}

namespace {

template <class T>
std::shared_ptr<const T> reference_of(const JobReference& reference) {
  const auto* kind = std::get_if<std::shared_ptr<const T>>(&reference);
  return kind ? *kind : nullptr;
}

}  // namespace

void ContourJob::validate() const {
  require(std::visit([](const auto& kind) { return kind != nullptr; }, reference), "trajectory: missing");
  const auto circle = reference_of<control::SpatialCircle>(reference);
  require(!circle || (std::isfinite(duration_s) && duration_s > 0.0),
          "duration: a circle in space needs a positive run length");
  require(axis_names.size() == reference_dimension(reference),
          "axes: the trajectory has " + std::to_string(reference_dimension(reference)) + " coordinates, the job " +
              std::to_string(axis_names.size()) + " axes");
  require(axes.size() == axis_count(), "plant: expected " + std::to_string(axis_count()) + " axes, got " +
                                           std::to_string(axes.size()));
  for (const auto& axis : axes) require(axis != nullptr, "plant: missing axis model");
  require(static_cast<bool>(controller_factory), "controller: missing");
  require(dead_zone_inverse.empty() || dead_zone_inverse.size() == axis_count(),
          "controller.dead_zone_inverse: expected one dead zone per axis of the group");
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
  require(contour_error_limit_m > 0.0, "contour_error_limit: expected a positive length");
  require(uplink.delay && uplink.loss && downlink.delay && downlink.loss,
          "delay: every link needs a delay and a loss model");
  require(!compensation || compensation->axis_models.size() == axis_count(),
          "compensation: expected a prediction model per axis of the group");
  require(!compensation || (compensation->horizon >= 1 && compensation->horizon <= DelayCompensation::kMaxHorizon),
          "compensation: expected a horizon of 1 to " + std::to_string(DelayCompensation::kMaxHorizon) + " commands");
  require(!initial_position || (static_cast<std::size_t>(initial_position->size()) == axis_count() &&
                                initial_position->allFinite()),
          "initial_position: expected finite coordinates, one per axis");
  const double run_s = run_length_s();
  // What must be kept per cycle bounds an iteration: an ILC's previous errors, commands and
  // directions (64 bytes a cycle) are 640 MB at 1e7 cycles; the delays are bounded apart
  // (DelayStatistics).
  require(run_s / sample_period_s <= 1e7,
          "duration: expected at most 1e7 cycles per iteration (run length / sample period), got " +
              std::to_string(run_s) + " s / " + std::to_string(sample_period_s) + " s");
  // The work ceiling of one job: 1e9 simulated cycles (about 15 minutes of one core).
  require(static_cast<double>(iterations) * (run_s / sample_period_s + 1.0) <= 1e9,
          "iterations: iterations x cycles per iteration is more than 1e9, the work ceiling of a job");
}

control::AxisVector ContourJob::start_position() const {
  if (initial_position) return *initial_position;
  return std::visit(
      [](const auto& kind) -> control::AxisVector {
        using Kind = std::decay_t<decltype(kind)>;
        if constexpr (std::is_same_v<Kind, std::shared_ptr<const control::MultiSineReference>>) {
          return control::AxisVector::Constant(1, kind->sample(0.0).position);
        } else {
          return kind->sample(0.0).position;
        }
      },
      reference);
}

double ContourJob::evaluation_start() const {
  return resolve_evaluation_start(evaluation_start_s,
                                  std::visit([](const auto& kind) { return kind->period_s(); }, reference));
}

std::shared_ptr<const control::GroupContour> ContourJob::contour() const {
  if (const auto circle = reference_of<control::SpatialCircle>(reference)) {
    return std::make_shared<control::SpatialContour>(circle, duration_s);
  }
  if (const auto track = reference_of<control::MultiSineReference>(reference)) {
    return std::make_shared<control::SingleAxisTrack>(track);
  }
  return std::make_shared<control::PlanarContour>(reference_of<control::ReferenceTrajectory>(reference));
}

std::unique_ptr<control::GroupController> ContourJob::make_controller() const {
  auto out = controller_factory();
  if (dead_zone_inverse.empty()) return out;
  return std::make_unique<control::DeadZoneCompensatedGroup>(std::move(out), dead_zone_inverse);
}

double ContourJob::run_length_s() const {
  if (duration_s > 0.0) return duration_s;
  return std::visit(
      [](const auto& kind) -> double {
        using Kind = std::decay_t<decltype(kind)>;
        if constexpr (std::is_same_v<Kind, std::shared_ptr<const control::SpatialCircle>>) {
          return 0.0;
        } else {
          return kind->duration_s();
        }
      },
      reference);
}

double ContourJob::reference_size_m() const {
  const auto group = contour();
  control::GroupReference point;
  control::AxisVector low, high;
  for (std::size_t k = 0; k < cycles(); ++k) {
    group->sample(static_cast<double>(k) * sample_period_s, point);
    if (k == 0) {
      low = high = point.position;
    } else {
      low = low.cwiseMin(point.position);
      high = high.cwiseMax(point.position);
    }
  }
  return cycles() == 0 ? 0.0 : (high - low).maxCoeff();
}

std::size_t ContourJob::cycles() const {
  return static_cast<std::size_t>(std::llround(run_length_s() / sample_period_s)) + 1;
}

}  // namespace netmc::sim
