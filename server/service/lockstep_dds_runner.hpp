#pragma once
// Runs a job on remote axis nodes over DDS in lockstep (virtual time): the server side is the
// same ContourServer as `netmc sim`, each axis node runs the same AxisEndpoint, and this class
// carries their calls as JobControl, Setpoint and Feedback samples in the same order. Results
// equal the in-process run bit for bit; a sample lost on the wire is repaired by DDS
// reliability within a few heartbeat periods (Delivery::exchange).

#include <atomic>
#include <chrono>
#include <functional>
#include <vector>

#include "dds_types.h"
#include "idl/job.pb.h"
#include "server/job/job_builder.hpp"
#include "server/service/dds_job_messages.hpp"
#include "server/sim/contour_server.hpp"

namespace netmc::service {

class LockstepDdsRunner {
 public:
  LockstepDdsRunner(const JobChannels& channels, const netmc::v1::JobSpec& spec,
                    std::uint64_t job_id, std::chrono::milliseconds axis_timeout,
                    const job::JobBuildOptions& build);

  // Runs every iteration (stopping after an unstable one or when `cancel` is set).
  void run(const std::function<void(const sim::IterationRecord&)>& on_iteration,
           const std::atomic<bool>& cancel);

  std::string controller_description() const { return server_.controller_description(); }
  std::size_t cycles() const { return server_.cycles(); }
  // A live view of the cycles (the console); see sim::CycleListener.
  void set_cycle_listener(std::shared_ptr<sim::CycleListener> listener) { server_.set_cycle_listener(std::move(listener)); }

 private:
  // Feedback of `cycle` in `iteration` from every axis, in axis order.
  std::vector<netmc::dds::Feedback> collect(std::uint32_t iteration, std::uint64_t cycle);

  const JobChannels& channels_;
  sim::ContourJob job_;
  sim::ContourServer server_;
  JobPublisher publisher_;
  std::chrono::milliseconds axis_timeout_;
};

}  // namespace netmc::service
