#pragma once
// Runs a job on remote axis nodes over DDS on the wall clock. The axes sample every period on
// their own timers; the server computes each cycle when the feedback of every axis has arrived
// (real DDS latency plus the uplink netsim delay) or at the deadline, with the same
// ContourServer as `netmc sim`. Delays are real plus emulated, so results vary from run to run.

#include <atomic>
#include <chrono>
#include <functional>
#include <map>

#include "server/service/dds_job_messages.hpp"
#include "server/sim/contour_server.hpp"

namespace netmc::service {

class RealtimeDdsRunner {
 public:
  // An axis that sends no feedback for `missed_cycles_limit` periods fails the job.
  RealtimeDdsRunner(JobChannels channels, const netmc::v1::JobSpec& spec, std::uint64_t job_id,
                    std::chrono::milliseconds axis_timeout, std::uint32_t missed_cycles_limit);

  void run(const std::function<void(const sim::IterationRecord&)>& on_iteration,
           const std::atomic<bool>& cancel);
  std::string controller_description() const { return server_.controller_description(); }

 private:
  // Takes feedback until `cycle`'s sample of every axis is in or `until` passes.
  void gather(std::uint32_t iteration, std::uint64_t cycle, double start_monotonic_s,
              std::chrono::steady_clock::time_point until);
  void submit(const netmc::dds::Feedback& feedback, double start_monotonic_s);

  JobChannels channels_;
  sim::ContourJob job_;
  sim::ContourServer server_;
  SetpointPublisher publisher_;
  std::chrono::milliseconds axis_timeout_;
  std::uint32_t missed_cycles_limit_;
  // Per iteration: which samples are in, finals, counters.
  std::map<std::pair<std::uint64_t, std::uint32_t>, bool> received_;
  std::vector<netmc::dds::Feedback> finals_;
  std::vector<bool> final_in_;
};

}  // namespace netmc::service
