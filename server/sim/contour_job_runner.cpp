#include "server/sim/contour_job_runner.hpp"

namespace netmc::sim {

ContourJobRunner::ContourJobRunner(ContourJob job) : job_(std::move(job)), server_(job_) {
  for (std::size_t axis = 0; axis < job_.axes.size(); ++axis) {
    axes_.emplace_back(AxisEndpoint::simulated_drive(job_, axis), job_, axis);
  }
}

IterationRecord ContourJobRunner::run_iteration() {
  const std::size_t iteration = completed_ + 1;
  const std::size_t cycles = server_.cycles();
  const double h = job_.sample_period_s;

  const control::AxisVector start = server_.begin_iteration(iteration);
  for (std::size_t axis = 0; axis < axes_.size(); ++axis) {
    axes_[axis].begin_iteration(iteration, start[static_cast<Eigen::Index>(axis)]);
  }
  for (std::size_t k = 0; k < cycles; ++k) {
    const double t = static_cast<double>(k) * h;
    // Axis nodes sample on their own clock and publish feedback k.
    for (std::size_t axis = 0; axis < axes_.size(); ++axis) {
      server_.submit_feedback(axis, k, t, axes_[axis].sample());
    }
    const CycleCommand command = server_.compute_cycle(k);
    if (command.diverged) break;
    for (std::size_t axis = 0; axis < axes_.size(); ++axis) {
      if (command.horizon_length > 0) {
        const auto first = command.horizon.begin() + static_cast<std::ptrdiff_t>(axis * command.horizon_length);
        axes_[axis].submit_packet(command.send_time_s, k, command.acts_at_s,
                                  {first, first + static_cast<std::ptrdiff_t>(command.horizon_length)});
      } else {
        axes_[axis].submit_setpoint(command.send_time_s, k, command.command[static_cast<Eigen::Index>(axis)],
                                    command.acts_at_s);
      }
    }
    if (k + 1 == cycles) break;
    // Axis nodes apply setpoints as they arrive during [t_k, t_k+1).
    for (std::size_t axis = 0; axis < axes_.size(); ++axis) {
      server_.record_applied(axis, axes_[axis].advance_to(static_cast<double>(k + 1) * h));
    }
  }
  std::uint64_t lost = 0, stale = 0, horizon = 0, held = 0;
  for (const auto& axis : axes_) {
    lost += axis.lost_setpoints();
    stale += axis.stale_setpoints();
    horizon += axis.horizon_cycles();
    held += axis.held_cycles();
  }
  server_.record_playout(horizon, held);
  ++completed_;
  return server_.end_iteration(lost, stale);
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
