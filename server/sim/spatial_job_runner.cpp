#include "server/sim/spatial_job_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "plant/plant_catalog.hpp"

namespace netmc::sim {

void SpatialJob::validate() const {
  const auto positive = [](double value, const char* field) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw std::invalid_argument(std::string(field) + ": expected a positive number");
    }
  };
  positive(revolutions, "revolutions");
  positive(sample_period_s, "sample_period_s");
  positive(divergence_limit_m, "divergence_limit_m");
  if (!(command_limit > 0.0)) throw std::invalid_argument("command_limit: expected a positive number");
  if (evaluation_start_s < 0.0) throw std::invalid_argument("evaluation_start_s: expected a number >= 0");
  if (duration_s() / sample_period_s > 1e8) {
    throw std::invalid_argument("revolutions: more than 1e8 samples at this sample period");
  }
  // Throws for a degenerate circle or an invalid gain.
  control::SpatialSarc sarc(gains, sample_period_s, std::make_shared<const control::SpatialCircle>(circle));
}

SpatialJobRunner::SpatialJobRunner(SpatialJob job) : job_(std::move(job)) {
  job_.validate();
  circle_ = std::make_shared<control::SpatialCircle>(job_.circle);
  auto plants = plant::make_plant_set(job_.plant_name, 3);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    axes_.emplace_back(std::move(plants.axes[axis]), job_.sensor, job_.command_limit, job_.downlink,
                       job_.seed, axis);
  }
}

std::string SpatialJobRunner::controller_description() const {
  const auto& g = job_.gains;
  return fmt::format("gtcf-sarc, three axes: Lambda = diag({:g}, {:g}, {:g}), K_s = diag({:g}, {:g}, {:g}), F_M = {:g} V",
                     g.lambda[0], g.lambda[1], g.lambda[2], g.feedback[0], g.feedback[1], g.feedback[2],
                     g.uncertainty_bound[0]);
}

SpatialIterationMetrics SpatialJobRunner::run() {
  const double h = job_.sample_period_s;
  const auto cycles = static_cast<std::size_t>(std::llround(job_.duration_s() / h)) + 1;
  const double window_s = job_.evaluation_start();
  control::SpatialSarc controller(job_.gains, h, circle_);
  const Eigen::Vector3d start = circle_->sample(0.0).position;
  for (std::size_t axis = 0; axis < 3; ++axis) axes_[axis].begin_iteration(1, start[static_cast<Eigen::Index>(axis)]);
  controller.begin(start);

  SpatialIterationMetrics m;
  double squares = 0.0, steady_squares = 0.0;
  std::array<double, 3> tracking_squares{}, command_squares{};
  std::size_t samples = 0, steady_samples = 0;
  std::vector<double> tau;
  tau.reserve(3 * cycles);
  for (std::size_t k = 0; k < cycles; ++k) {
    const double t = static_cast<double>(k) * h;
    const auto reference = circle_->sample(t);
    Eigen::Vector3d measured, truth;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const AxisSample s = axes_[axis].sample();
      measured[static_cast<Eigen::Index>(axis)] = s.measured_m;
      truth[static_cast<Eigen::Index>(axis)] = s.true_position_m;
    }
    const double e = circle_->distance(truth);
    if (!std::isfinite(e) || e > job_.divergence_limit_m) {
      m.diverged = true;
      m.diverged_at_s = t;
      break;
    }
    ++samples;
    squares += e * e;
    m.e_sum_m += e;
    m.e_max_m = std::max(m.e_max_m, e);
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const double d = truth[static_cast<Eigen::Index>(axis)] - reference.position[static_cast<Eigen::Index>(axis)];
      tracking_squares[axis] += d * d;
    }
    const Eigen::Vector3d u = controller.step(reference, measured);
    if (!u.allFinite()) {
      m.diverged = true;
      m.diverged_at_s = t;
      break;
    }
    if (t >= window_s) {
      ++steady_samples;
      steady_squares += e * e;
      m.e_max_steady_m = std::max(m.e_max_steady_m, e);
      for (std::size_t axis = 0; axis < 3; ++axis) {
        const double applied = std::min(std::abs(u[static_cast<Eigen::Index>(axis)]), job_.command_limit);
        command_squares[axis] += applied * applied;
      }
    }
    for (std::size_t axis = 0; axis < 3; ++axis) axes_[axis].submit_setpoint(t, k, u[static_cast<Eigen::Index>(axis)]);
    if (k + 1 == cycles) break;
    for (auto& axis : axes_) {
      for (const auto& a : axis.advance_to(static_cast<double>(k + 1) * h)) {
        tau.push_back(a.arrival_time_s - static_cast<double>(a.sequence) * h);
      }
    }
  }
  const auto root_mean = [](double sum, std::size_t n) { return n == 0 ? 0.0 : std::sqrt(sum / static_cast<double>(n)); };
  m.e_rms_m = root_mean(squares, samples);
  m.e_rms_steady_m = root_mean(steady_squares, steady_samples);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    m.tracking_rms_m[axis] = root_mean(tracking_squares[axis], samples);
    m.command_rms_steady[axis] = root_mean(command_squares[axis], steady_samples);
    m.lost_setpoints += axes_[axis].lost_setpoints();
    m.stale_setpoints += axes_[axis].stale_setpoints();
  }
  if (!tau.empty()) {
    std::sort(tau.begin(), tau.end());
    double sum = 0.0;
    for (const double value : tau) sum += value;
    m.tau_mean_s = sum / static_cast<double>(tau.size());
    m.tau_p99_s = tau[static_cast<std::size_t>(0.99 * static_cast<double>(tau.size() - 1))];
    m.tau_max_s = tau.back();
  }
  return m;
}

}  // namespace netmc::sim
