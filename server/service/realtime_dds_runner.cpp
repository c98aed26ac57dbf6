#include "server/service/realtime_dds_runner.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <thread>

#include "server/job/job_builder.hpp"

namespace netmc::service {
namespace {

using Clock = std::chrono::steady_clock;

// Lead time between announcing an iteration and its t = 0, so every axis has the BEGIN sample
// (and, in iteration 1, has built the job) before its first tick.
constexpr double kStartLeadS = 0.25;

// Longest poll for the rest of a cycle's feedback (and at most a tenth of the period).
constexpr std::chrono::microseconds kGatherSpinMax{50};

}  // namespace

RealtimeDdsRunner::RealtimeDdsRunner(const JobChannels& channels, const netmc::v1::JobSpec& spec,
                                     std::uint64_t job_id, RealtimeLimits limits, dds::TimeBase time_base,
                                     ClockOffsets offsets, const job::JobBuildOptions& build)
    : channels_(channels),
      job_(job::build_contour_job(spec, build)),
      server_(job_),
      publisher_(channels, spec, job_id),
      limits_(limits),
      time_base_(time_base),
      offsets_(std::move(offsets)) {}

void RealtimeDdsRunner::gather(std::uint32_t iteration, std::uint64_t cycle, Clock::time_point until) {
  const std::size_t axes = job_.axes.size();
  const auto complete = [&] {
    for (std::size_t axis = 0; axis < axes; ++axis) {
      if (!received_[axis][cycle]) return false;
    }
    return true;
  };
  // Once the first axis's sample of the cycle is in, the others are a few microseconds behind
  // (written back to back by a node, or by nodes sampling in step): polling for them for a short
  // while saves the sleep and wake-up of a second wait, which on a virtual machine costs more.
  const auto spin = std::chrono::duration_cast<Clock::duration>(
      std::min(std::chrono::duration<double>(kGatherSpinMax), std::chrono::duration<double>(job_.sample_period_s / 10)));
  std::optional<Clock::time_point> spin_until;
  while (!complete()) {
    std::optional<netmc::dds::Feedback> sample;
    if (spin_until && Clock::now() < std::min(*spin_until, until)) {
      sample = channels_.feedback->try_take();
      if (!sample) continue;
    } else {
      sample = channels_.feedback->take_until(until);
      if (!sample) return;  // deadline: the cycle runs with the newest feedback it has
    }
    const std::size_t axis = axis_index(channels_, sample->axis());
    if (sample->server() != channels_.server || sample->job_id() != publisher_.job_id() ||
        sample->iteration() != iteration || axis >= axes || sample->kind() != netmc::dds::FEEDBACK_SAMPLE ||
        !from_axis_node(channels_, axis, channels_.feedback->last_sender()) ||
        sample->cycle() >= received_[axis].size() || received_[axis][sample->cycle()]) {
      continue;
    }
    received_[axis][sample->cycle()] = 1;
    ++received_count_[axis];
    last_heard_[axis] = Clock::now();
    if (sample->cycle() == cycle && !spin_until) spin_until = last_heard_[axis] + spin;
    std::vector<sim::AppliedSetpoint> applied;
    for (const auto& a : sample->applied()) {
      applied.push_back({a.cycle(), a.send_time_s(), a.arrival_time_s(), a.network_arrival_s(), a.horizon_index()});
    }
    server_.record_applied(axis, applied);
    // The feedback enters the emulated uplink when it reaches the server: real latency + netsim.
    server_.submit_feedback(axis, sample->cycle(), job_time_s(), {sample->position_m(), sample->true_position_m()});
  }
}

void RealtimeDdsRunner::prepare(std::uint32_t iteration, const control::AxisVector& start,
                                const std::atomic<bool>& cancel) {
  const std::size_t axes = job_.axes.size();
  for (std::size_t axis = 0; axis < axes; ++axis) {
    publisher_.prepare_iteration(axis, iteration, start[static_cast<Eigen::Index>(axis)]);
  }
  // A simulated axis is ready at once; hardware is moved back to the start first.
  std::vector<bool> ready(axes, false);
  std::size_t waiting = axes;
  const auto deadline = Clock::now() + limits_.positioning_timeout;
  while (waiting > 0 && !cancel.load()) {
    const bool got = wait_axis_event(channels_, publisher_.job_id(), std::min(deadline, Clock::now() + std::chrono::milliseconds(100)),
                                     [&](const netmc::dds::AxisEvent& event) {
                                       const std::size_t axis = axis_index(channels_, event.axis());
                                       if (event.kind() != netmc::dds::AXIS_READY || event.iteration() != iteration ||
                                           ready[axis]) {
                                         return;
                                       }
                                       ready[axis] = true;
                                       --waiting;
                                     });
    if (!got && Clock::now() >= deadline) {
      std::string names;
      for (std::size_t axis = 0; axis < axes; ++axis) {
        if (!ready[axis]) names += (names.empty() ? "" : ", ") + channels_.axes[axis];
      }
      throw JobFailure("axis " + names + " was not ready for iteration " + std::to_string(iteration) + " within " +
                       std::to_string(limits_.positioning_timeout.count()) +
                       " ms (at rest at its start; netmc-server --positioning-timeout)");
    }
  }
}

void RealtimeDdsRunner::run(const std::function<void(const sim::IterationRecord&)>& on_iteration,
                            const std::atomic<bool>& cancel) {
  const std::size_t axes = job_.axes.size();
  const std::size_t cycles = server_.cycles();
  const double h = job_.sample_period_s;
  const double silence_s = std::chrono::duration<double>(limits_.silence_limit).count();
  try {
    for (std::uint32_t iteration = 1; iteration <= job_.iterations && !cancel.load(); ++iteration) {
      const control::AxisVector start = server_.begin_iteration(iteration);
      prepare(iteration, start, cancel);
      if (cancel.load()) break;
      // On the grid of whole periods of the server's clock: the jobs of one server that share a
      // period then sample in phase, and a node hosting axes of several of them takes all their
      // samples in one wake-up instead of one each.
      t0_s_ = std::ceil((dds::time_base_now_s(time_base_) + kStartLeadS) / h) * h;
      const Clock::time_point t0_steady = dds::steady_time_at(time_base_, t0_s_);
      double uncertainty = 0.0;
      for (std::size_t axis = 0; axis < axes; ++axis) {
        // Each node starts the iteration on its own clock: t0 plus its measured offset.
        const netsim::ClockOffsetEstimate clock = offsets_(axis);
        uncertainty = std::max(uncertainty, clock.uncertainty_s);
        publisher_.begin_iteration(axis, iteration, start[static_cast<Eigen::Index>(axis)], t0_s_ + clock.offset_s,
                                   false);
      }
      received_.assign(axes, std::vector<char>(cycles, 0));
      received_count_.assign(axes, 0);
      last_heard_.assign(axes, t0_steady);
      bool stopped_early = false;
      std::uint64_t commands_sent = 0;
      for (std::size_t k = 0; k < cycles; ++k) {
        const double t = static_cast<double>(k) * h;
        gather(iteration, k, dds::steady_time_at(time_base_, t0_s_ + t + job_.deadline()));
        poll_axis_events(channels_, publisher_.job_id(), nullptr);
        const auto now = Clock::now();
        for (std::size_t axis = 0; axis < axes; ++axis) {
          const double silent_s = std::chrono::duration<double>(now - last_heard_[axis]).count();
          if (silent_s > silence_s) {
            throw JobFailure("axis " + channels_.axes[axis] + " sent no feedback for " +
                             std::to_string(static_cast<long>(silent_s * 1e3)) + " ms (" +
                             std::to_string(static_cast<long>(silent_s / h)) + " periods, limit " +
                             std::to_string(limits_.silence_limit.count()) + " ms) at cycle " +
                             std::to_string(k) + " of iteration " + std::to_string(iteration) +
                             ": node stopped or unreachable");
          }
        }
        // Act when the emulated uplink delivers (or at the deadline), as ContourServer decides.
        std::this_thread::sleep_until(dds::steady_time_at(time_base_, t0_s_ + server_.compute_time(k)));
        const auto ready = Clock::now();
        const sim::CycleCommand command = server_.compute_cycle(k);
        if (!command.limit_exceeded.empty()) {
          // Hardware must not run on past the job's limit: the drives' own quick stop, at once.
          publisher_.quick_stop(iteration);
          throw JobFailure(command.limit_exceeded + " of iteration " + std::to_string(iteration) +
                           ": the axes were quick-stopped");
        }
        if (command.diverged || cancel.load()) {
          stopped_early = !command.diverged;
          break;
        }
        const auto departure = Clock::now();
        const double sent_at = job_time_s();
        // The planned travel is kept from the real departure, which a loaded host may delay;
        // with packets the instant stays on its grid (a late setpoint starts at a later one).
        const double acts_at =
            command.horizon_length > 0 ? command.acts_at_s : command.acts_at_s + (sent_at - command.send_time_s);
        for (std::size_t axis = 0; axis < axes; ++axis) {
          publisher_.command(axis, iteration, k, command, sent_at, acts_at);
        }
        ++commands_sent;
        server_.correct_compute_delay(std::chrono::duration<double>(departure - ready).count());
      }
      for (std::size_t axis = 0; axis < axes; ++axis) publisher_.end_iteration(axis, iteration, commands_sent);
      // The axes' reports carry their downlink counters; the iteration ends as soon as all are
      // in (each axis sends its report two periods, at least 10 ms, after END_ITERATION).
      std::vector<netmc::dds::AxisEvent> ended(axes);
      std::vector<bool> ended_in(axes, false);
      std::size_t reports = 0;
      const auto final_deadline = Clock::now() + limits_.axis_timeout;
      while (reports < axes) {
        const bool got = wait_axis_event(channels_, publisher_.job_id(), final_deadline,
                                         [&](const netmc::dds::AxisEvent& event) {
                                           const std::size_t axis = axis_index(channels_, event.axis());
                                           if (event.iteration() != iteration || ended_in[axis]) return;
                                           ended[axis] = event;
                                           ended_in[axis] = true;
                                           ++reports;
                                         });
        if (!got && Clock::now() >= final_deadline) {
          for (std::size_t axis = 0; axis < axes; ++axis) {
            if (!ended_in[axis]) {
              throw JobFailure("axis " + channels_.axes[axis] + " did not confirm the end of iteration " +
                               std::to_string(iteration) + " within " +
                               std::to_string(limits_.axis_timeout.count()) + " ms");
            }
          }
        }
      }
      while (channels_.feedback->try_take()) {
      }  // late samples of this iteration: counted by the axes, not used
      std::uint64_t lost = 0, stale = 0, lost_feedback = 0, horizon = 0, held = 0;
      for (std::size_t axis = 0; axis < axes; ++axis) {
        lost += ended[axis].lost_setpoints() + ended[axis].missing_setpoints();
        stale += ended[axis].stale_setpoints();
        horizon += ended[axis].horizon_cycles();
        held += ended[axis].held_cycles();
        if (ended[axis].samples() > received_count_[axis]) lost_feedback += ended[axis].samples() - received_count_[axis];
      }
      server_.record_playout(horizon, held);
      sim::IterationRecord record = server_.end_iteration(lost, stale);
      record.metrics.lost_feedback += lost_feedback;
      record.metrics.clock_uncertainty_s = uncertainty;
      if (stopped_early) break;
      publish_iteration_log(channels_, publisher_.job_id(), job_, record);
      if (on_iteration) on_iteration(record);
      if (record.metrics.diverged) break;
    }
  } catch (...) {
    publisher_.end_job();
    throw;
  }
  publisher_.end_job();
}

}  // namespace netmc::service
