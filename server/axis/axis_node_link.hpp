#pragma once
// What both kinds of axis node (lockstep, realtime) share: the node's identity, its DDS
// endpoints (setpoints in; feedback and status out) and the start of a job from its spec.

#include <memory>
#include <string>
#include <vector>

#include "dds_types.h"
#include "server/dds/dds_context.hpp"
#include "server/sim/axis_endpoint.hpp"

namespace netmc::axis {

struct AxisNodeConfig {
  std::string node;                    // unique node name
  std::vector<std::uint32_t> axis_ids; // 0 = x, 1 = y
  std::string plant = "seed001";       // the plant model this node hosts
  std::string clock = "lockstep";
};

// One axis of a job as a node runs it.
struct JobAxis {
  std::unique_ptr<sim::AxisEndpoint> endpoint;
  std::uint64_t job_id = 0;
  std::size_t cycles = 0;
  double sample_period_s = 0.0;
};

class AxisNodeLink {
 public:
  AxisNodeLink(dds::DdsContext& context, AxisNodeConfig config);

  const AxisNodeConfig& config() const { return config_; }
  dds::SampleReader<netmc::dds::Setpoint>& setpoints() { return setpoints_; }
  void publish(netmc::dds::Feedback& feedback) { feedback_writer_->write(&feedback); }
  void publish_status(netmc::dds::NodeHealth health, const std::string& detail);
  // From the BEGIN_ITERATION setpoint of iteration 1: the job's axis, built from its spec.
  JobAxis start_job(const netmc::dds::Setpoint& begin);

 private:
  AxisNodeConfig config_;
  eprosima::fastdds::dds::DataWriter* feedback_writer_;
  eprosima::fastdds::dds::DataWriter* status_writer_;
  dds::SampleReader<netmc::dds::Setpoint> setpoints_;
};

// Copies setpoints applied by the actuator into a feedback sample.
void append_applied(netmc::dds::Feedback& feedback, const std::vector<sim::AppliedSetpoint>& applied);
// Fills the sample fields of a feedback.
void set_sample(netmc::dds::Feedback& feedback, std::uint64_t cycle, double time_s,
                const sim::AxisSample& sample);

}  // namespace netmc::axis
