#pragma once
// Runs a job on remote axis nodes over DDS on the wall clock. The axes sample every period on
// their own timers and clocks; the server computes each cycle when the feedback of every axis
// has arrived (real DDS latency plus the uplink netsim delay) or at the deadline, with the same
// ContourServer as `netmc sim`. Nothing waits for a lost sample: a lost feedback leaves the
// server computing with the newest it has, a lost setpoint leaves the axis's last command in
// force, and both are counted. Delays are real plus emulated, so results vary from run to run.

#include <atomic>
#include <chrono>
#include <functional>
#include <vector>

#include "netsim/clock_offset_estimator.hpp"
#include "server/dds/time_base.hpp"
#include "server/job/job_builder.hpp"
#include "server/service/dds_job_messages.hpp"
#include "server/sim/contour_server.hpp"

namespace netmc::service {

struct RealtimeLimits {
  std::chrono::milliseconds axis_timeout{2000};   // for the axes' end-of-iteration reports
  std::chrono::milliseconds silence_limit{500};   // an axis silent this long fails the job
  // For every axis to stand ready at an iteration's start (hardware is moved there).
  std::chrono::milliseconds positioning_timeout{60000};
};

// The clock of axis `axis`'s node against the server's (throws JobFailure if unknown).
using ClockOffsets = std::function<netsim::ClockOffsetEstimate(std::size_t axis)>;

class RealtimeDdsRunner {
 public:
  RealtimeDdsRunner(const JobChannels& channels, const netmc::v1::JobSpec& spec, std::uint64_t job_id,
                    RealtimeLimits limits, dds::TimeBase time_base, ClockOffsets offsets,
                    const job::JobBuildOptions& build);

  void run(const std::function<void(const sim::IterationRecord&)>& on_iteration,
           const std::atomic<bool>& cancel);
  std::string controller_description() const { return server_.controller_description(); }
  std::size_t cycles() const { return server_.cycles(); }
  // A live view of the cycles (the console); see sim::CycleListener.
  void set_cycle_listener(std::shared_ptr<sim::CycleListener> listener) { server_.set_cycle_listener(std::move(listener)); }

 private:
  // Takes feedback until `cycle`'s sample of every axis is in or `until` passes; samples of
  // older cycles that come late are used too (the newest wins in ContourServer).
  void gather(std::uint32_t iteration, std::uint64_t cycle, std::chrono::steady_clock::time_point until);
  // PREPARE_ITERATION to every axis, then waits for each one's AXIS_READY (throws JobFailure
  // naming the axes not ready within the positioning timeout).
  void prepare(std::uint32_t iteration, const control::AxisVector& start, const std::atomic<bool>& cancel);
  double job_time_s() const { return dds::time_base_now_s(time_base_) - t0_s_; }

  const JobChannels& channels_;
  sim::ContourJob job_;
  sim::ContourServer server_;
  JobPublisher publisher_;
  RealtimeLimits limits_;
  dds::TimeBase time_base_;
  ClockOffsets offsets_;
  // State of the current iteration.
  double t0_s_ = 0.0;                                      // t = 0 on the server's clock
  std::vector<std::vector<char>> received_;                // [axis][cycle]
  std::vector<std::uint64_t> received_count_;
  std::vector<std::chrono::steady_clock::time_point> last_heard_;
};

}  // namespace netmc::service
