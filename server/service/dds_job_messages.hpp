#pragma once
// What netmc-server's job runners (lockstep and realtime) say over DDS: setpoints of every kind,
// the end of a job, and the iteration log.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "dds_types.h"
#include "idl/job.pb.h"
#include "server/dds/dds_context.hpp"
#include "server/sim/contour_job.hpp"
#include "server/sim/iteration_metrics.hpp"

namespace netmc::service {

// An axis node stopped answering or reported a fault: the job cannot go on.
class JobFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct JobChannels {
  eprosima::fastdds::dds::DataWriter* setpoints = nullptr;
  dds::SampleReader<netmc::dds::Feedback>* feedback = nullptr;
  eprosima::fastdds::dds::DataWriter* iteration_logs = nullptr;
};

class SetpointPublisher {
 public:
  SetpointPublisher(eprosima::fastdds::dds::DataWriter* writer, const netmc::v1::JobSpec& spec,
                    std::uint64_t job_id);
  void publish(std::uint32_t axis, std::uint32_t iteration, std::uint64_t cycle,
               netmc::dds::SetpointKind kind, double command, double send_time_s,
               double start_position_m, bool with_spec, double start_monotonic_s);
  void end_job(std::uint32_t axes);
  std::uint64_t job_id() const { return job_id_; }

 private:
  eprosima::fastdds::dds::DataWriter* writer_;
  std::vector<std::uint8_t> spec_bytes_;
  std::uint64_t job_id_;
};

void publish_iteration_log(eprosima::fastdds::dds::DataWriter* writer, std::uint64_t job_id,
                           const sim::ContourJob& job, const sim::IterationRecord& record);

// The spec the axes receive: delay traces are inlined, since the trace file lives on the server.
netmc::v1::JobSpec spec_for_axes(const netmc::v1::JobSpec& spec);

std::string axis_name(std::size_t axis);

}  // namespace netmc::service
