#include "server/sim/contour_job.hpp"

#include <cmath>
#include <stdexcept>

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
  require(trajectory != nullptr, "trajectory: missing");
  require(axes.size() == 2, "plant: expected 2 axes, got " + std::to_string(axes.size()));
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
  require(!initial_position || initial_position->allFinite(),
          "initial_position: expected finite coordinates");
  const double run_s = duration_s > 0.0 ? duration_s : trajectory->duration_s();
  require(run_s / sample_period_s <= 1e8,
          "sample_period: too many cycles for the run length (more than 1e8)");
}

Eigen::Vector2d ContourJob::start_position() const {
  return initial_position ? *initial_position : Eigen::Vector2d(trajectory->sample(0.0).position);
}

double ContourJob::evaluation_start() const {
  return resolve_evaluation_start(evaluation_start_s, trajectory->period_s());
}

std::size_t ContourJob::cycles() const {
  const double run_s = duration_s > 0.0 ? duration_s : trajectory->duration_s();
  return static_cast<std::size_t>(std::llround(run_s / sample_period_s)) + 1;
}

}  // namespace netmc::sim
