#pragma once
// netmc-axis in lockstep mode: virtual time advances one period per setpoint. Each owned axis
// runs the same AxisEndpoint as the in-process simulation (plant, sensor, actuator, downlink
// netsim), so a distributed lockstep run reproduces `netmc sim` bit for bit.

#include <atomic>
#include <map>

#include "server/axis/axis_node_link.hpp"

namespace netmc::axis {

class LockstepAxisNode {
 public:
  LockstepAxisNode(dds::DdsContext& context, AxisNodeConfig config);
  AxisNodeLink& link() { return link_; }
  // Serves job control and setpoints until `stop` becomes true.
  void serve(const std::atomic<bool>& stop);

 private:
  void handle(const netmc::dds::JobControl& control);
  void publish_status();
  void handle(const netmc::dds::Setpoint& setpoint);

  AxisNodeLink link_;
  std::map<std::string, JobAxis> axes_;
};

}  // namespace netmc::axis
