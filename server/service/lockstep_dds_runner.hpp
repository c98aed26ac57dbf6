#pragma once
// Runs a job on remote axis nodes over DDS in lockstep (virtual time): the server side is the
// same ContourServer as `netmc sim`, each axis node runs the same AxisEndpoint, and this class
// carries their calls as Setpoint and Feedback samples in the same order. Results equal the
// in-process run bit for bit.

#include <atomic>
#include <chrono>
#include <functional>
#include <stdexcept>
#include <vector>

#include "dds_types.h"
#include "idl/job.pb.h"
#include "server/dds/dds_context.hpp"
#include "server/sim/contour_server.hpp"

namespace netmc::service {

// An axis node stopped answering or reported a fault: the job cannot go on.
class JobFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LockstepChannels {
  eprosima::fastdds::dds::DataWriter* setpoints = nullptr;
  dds::SampleReader<netmc::dds::Feedback>* feedback = nullptr;
  eprosima::fastdds::dds::DataWriter* iteration_logs = nullptr;
};

class LockstepDdsRunner {
 public:
  LockstepDdsRunner(LockstepChannels channels, const netmc::v1::JobSpec& spec,
                    std::uint64_t job_id, std::chrono::milliseconds axis_timeout);

  // Runs every iteration (stopping after an unstable one or when `cancel` is set).
  void run(const std::function<void(const sim::IterationRecord&)>& on_iteration,
           const std::atomic<bool>& cancel);

  std::string controller_description() const { return server_.controller_description(); }

 private:
  void publish(std::uint32_t axis, std::uint32_t iteration, std::uint64_t cycle,
               netmc::dds::SetpointKind kind, double command, double send_time_s,
               double start_position_m, bool with_spec);
  // Feedback of `cycle` in `iteration` from every axis, in axis order.
  std::vector<netmc::dds::Feedback> collect(std::uint32_t iteration, std::uint64_t cycle);
  void end_job();

  LockstepChannels channels_;
  sim::ContourJob job_;
  sim::ContourServer server_;
  std::vector<std::uint8_t> spec_bytes_;
  std::uint64_t job_id_;
  std::chrono::milliseconds axis_timeout_;
};

// The spec the axes receive: delay traces are inlined, since the trace file lives on the server.
netmc::v1::JobSpec spec_for_axes(const netmc::v1::JobSpec& spec);

}  // namespace netmc::service
