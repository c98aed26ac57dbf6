#include "server/sim/contour_job_runner.hpp"

#include <algorithm>
#include <cmath>

namespace netmc::sim {
namespace {

// Independent random streams per link, axis and iteration, all derived from the job seed.
constexpr std::uint64_t kUplinkStream = 1;
constexpr std::uint64_t kDownlinkStream = 2;
constexpr std::uint64_t kSensorStream = 3;

std::uint64_t stream_id(std::uint64_t kind, std::size_t axis, std::size_t iteration) {
  return (static_cast<std::uint64_t>(iteration) << 16) | (static_cast<std::uint64_t>(axis) << 8) |
         kind;
}

netsim::DelayedChannel<double> make_channel(const LinkProfile& link, std::uint64_t seed,
                                            std::uint64_t stream) {
  return netsim::DelayedChannel<double>(netsim::LinkModel(
      link.delay->clone(), link.loss->clone(), netsim::RandomStream(seed, stream)));
}

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const auto rank = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size())));
  const std::size_t index = std::min(values.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

double mean(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

}  // namespace

ContourJobRunner::ContourJobRunner(ContourJob job)
    : job_((job.validate(), std::move(job))),
      controller_(control::make_contouring_controller(job_.controller_name, job_.controller,
                                                      job_.sample_period_s)) {
  for (std::size_t axis = 0; axis < job_.axes.size(); ++axis) {
    axes_.emplace_back(job_.axes[axis]->clone(),
                       plant::PositionSensor(job_.sensor, job_.seed,
                                             stream_id(kSensorStream, axis, 0)),
                       job_.command_limit);
    uplinks_.push_back(make_channel(job_.uplink, job_.seed, stream_id(kUplinkStream, axis, 0)));
    downlinks_.push_back(
        make_channel(job_.downlink, job_.seed, stream_id(kDownlinkStream, axis, 0)));
  }
}

IterationRecord ContourJobRunner::run_iteration() {
  const std::size_t cycles = job_.cycles();
  const double h = job_.sample_period_s;
  const std::size_t axis_count = axes_.size();
  const std::size_t iteration = completed_ + 1;

  // Every iteration starts from the same initial state (reset in simulation, a homing move on
  // hardware); nothing from the previous iteration is left in flight.
  const Eigen::Vector2d start = job_.trajectory->sample(0.0).position;
  for (std::size_t axis = 0; axis < axis_count; ++axis) {
    axes_[axis].reset(start[static_cast<Eigen::Index>(axis)]);
    uplinks_[axis].reset(netsim::RandomStream(job_.seed, stream_id(kUplinkStream, axis, iteration)));
    downlinks_[axis].reset(
        netsim::RandomStream(job_.seed, stream_id(kDownlinkStream, axis, iteration)));
  }
  controller_.begin_iteration(start, cycles);

  IterationRecord record;
  IterationMetrics& m = record.metrics;
  m.iteration = iteration;
  if (job_.record_traces) record.trace.resize(cycles);

  Eigen::Vector2d server_measurement = start;       // newest feedback the server holds
  std::vector<std::int64_t> newest_sequence(axis_count, -1);
  std::vector<double> tau, tau_sc, tau_ca;
  tau.reserve(cycles * axis_count);
  double squared_error_sum = 0.0;
  std::array<double, 2> tracking_squares{}, command_squares{};
  double compute_time = 0.0;
  std::size_t samples = 0;  // cycles completed before a divergence, if any

  for (std::size_t k = 0; k < cycles; ++k) {
    const double t = static_cast<double>(k) * h;
    const control::ReferencePoint reference = job_.trajectory->sample(t);

    // Axis nodes: sample on their own clock and publish feedback k.
    Eigen::Vector2d true_position, measured;
    for (std::size_t axis = 0; axis < axis_count; ++axis) {
      const auto i = static_cast<Eigen::Index>(axis);
      true_position[i] = axes_[axis].plant().position();
      measured[i] = axes_[axis].measure();
      if (!uplinks_[axis].send(t, k, measured[i])) ++m.lost_feedback;
    }

    // Server: event-driven, computes cycle k when feedback k of every axis is in, or at the
    // deadline with the newest feedback it has. Only messages of cycles <= k are in flight.
    const double deadline = t + job_.deadline();
    bool complete = true;
    double last_arrival = t;
    for (std::size_t axis = 0; axis < axis_count; ++axis) {
      bool arrived = false;
      for (const auto& delivery : uplinks_[axis].receive_until(deadline)) {
        const auto sequence = static_cast<std::int64_t>(delivery.sequence);
        if (sequence > newest_sequence[axis]) {
          newest_sequence[axis] = sequence;
          server_measurement[static_cast<Eigen::Index>(axis)] = delivery.payload;
        }
        if (delivery.sequence == k) {
          arrived = true;
          last_arrival = std::max(last_arrival, delivery.arrival_time_s);
          tau_sc.push_back(delivery.arrival_time_s - t);
        }
      }
      complete = complete && arrived;
    }
    if (!complete) ++m.deadline_misses;
    compute_time = std::max(compute_time, complete ? last_arrival : deadline);

    const control::ContouringCycle cycle = controller_.step(k, reference, server_measurement);
    const double contour_error = job_.trajectory->contour_error(true_position);
    if (!(std::abs(contour_error) <= job_.divergence_limit_m) || !cycle.command.allFinite()) {
      m.diverged = true;
      m.diverged_at_s = t;
      break;
    }
    ++samples;
    const double send_time = compute_time + job_.compute_delay_s;
    for (std::size_t axis = 0; axis < axis_count; ++axis) {
      if (!downlinks_[axis].send(send_time, k, cycle.command[static_cast<Eigen::Index>(axis)])) {
        ++m.lost_setpoints;
      }
    }

    // Metrics from the true plant state and the exact contour.
    m.e_max_m = std::max(m.e_max_m, std::abs(contour_error));
    m.e_sum_m += std::abs(contour_error);
    squared_error_sum += contour_error * contour_error;
    for (std::size_t axis = 0; axis < axis_count; ++axis) {
      const auto i = static_cast<Eigen::Index>(axis);
      const double tracking = reference.position[i] - true_position[i];
      tracking_squares[axis] += tracking * tracking;
      m.tracking_max_m[axis] = std::max(m.tracking_max_m[axis], std::abs(tracking));
      command_squares[axis] += cycle.command[i] * cycle.command[i];
    }
    if (job_.record_traces) {
      CycleTrace& row = record.trace[k];
      row.time_s = t;
      for (std::size_t axis = 0; axis < axis_count; ++axis) {
        const auto i = static_cast<Eigen::Index>(axis);
        row.reference_m[axis] = reference.position[i];
        row.position_m[axis] = true_position[i];
        row.measured_m[axis] = measured[i];
        row.axis_command[axis] = cycle.axis_command[i];
        row.command[axis] = cycle.command[i];
      }
      row.contour_error_m = contour_error;
      row.contour_error_estimate_m = cycle.estimate.contour_error;
      row.coupling_command = cycle.coupling_command;
    }

    // Axis nodes: apply setpoints as they arrive during [t_k, t_k+1).
    if (k + 1 == cycles) break;
    const double next_t = static_cast<double>(k + 1) * h;
    for (std::size_t axis = 0; axis < axis_count; ++axis) {
      const auto deliveries = downlinks_[axis].receive_until(next_t);
      for (const auto& delivery : deliveries) {
        const double loop_delay =
            delivery.arrival_time_s - static_cast<double>(delivery.sequence) * h;
        tau.push_back(loop_delay);
        tau_ca.push_back(delivery.arrival_time_s - delivery.send_time_s);
        if (job_.record_traces && axis == 0) record.trace[delivery.sequence].tau_s = loop_delay;
      }
      axes_[axis].advance_to(next_t, deliveries);
    }
  }

  if (job_.record_traces) record.trace.resize(samples);
  const auto n = static_cast<double>(std::max<std::size_t>(samples, 1));
  m.e_rms_m = std::sqrt(squared_error_sum / n);
  for (std::size_t axis = 0; axis < axis_count; ++axis) {
    m.tracking_rms_m[axis] = std::sqrt(tracking_squares[axis] / n);
    m.command_rms[axis] = std::sqrt(command_squares[axis] / n);
    m.stale_setpoints += axes_[axis].stale_setpoints();
  }
  m.tau_mean_s = mean(tau);
  m.tau_max_s = tau.empty() ? 0.0 : *std::max_element(tau.begin(), tau.end());
  m.tau_p99_s = percentile(tau, 0.99);
  m.tau_sc_mean_s = mean(tau_sc);
  m.tau_ca_mean_s = mean(tau_ca);

  controller_.end_iteration();
  ++completed_;
  return record;
}

std::vector<IterationRecord> ContourJobRunner::run_all(
    const std::function<void(const IterationRecord&)>& on_iteration) {
  std::vector<IterationRecord> records;
  while (completed_ < job_.iterations) {
    records.push_back(run_iteration());
    if (on_iteration) on_iteration(records.back());
    if (records.back().metrics.diverged) break;
  }
  return records;
}

}  // namespace netmc::sim
