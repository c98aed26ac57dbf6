#pragma once
// netmc-axis in lockstep mode: virtual time advances one period per setpoint. Each owned axis
// runs the same AxisEndpoint as the in-process simulation (plant, sensor, actuator, downlink
// netsim), so a distributed lockstep run reproduces `netmc sim` bit for bit.

#include <atomic>
#include <map>
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
};

class LockstepAxisNode {
 public:
  LockstepAxisNode(dds::DdsContext& context, AxisNodeConfig config);
  // Serves setpoints until `stop` becomes true.
  void serve(const std::atomic<bool>& stop);

 private:
  void handle(const netmc::dds::Setpoint& setpoint);
  void publish_status(netmc::dds::NodeHealth health, const std::string& detail);

  struct OwnedAxis {
    std::unique_ptr<sim::AxisEndpoint> endpoint;
    std::uint64_t job_id = 0;
    std::size_t cycles = 0;
    double sample_period_s = 0.0;
  };

  AxisNodeConfig config_;
  eprosima::fastdds::dds::DataWriter* feedback_writer_;
  eprosima::fastdds::dds::DataWriter* status_writer_;
  dds::SampleReader<netmc::dds::Setpoint> setpoints_;
  std::map<std::uint32_t, OwnedAxis> axes_;
};

}  // namespace netmc::axis
