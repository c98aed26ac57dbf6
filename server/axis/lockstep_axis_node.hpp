#pragma once
// netmc-axis in lockstep mode: virtual time advances one period per setpoint. Each owned axis
// runs the same AxisEndpoint as the in-process simulation (netmc's simulated drive under its
// supervision, sensor, downlink netsim), so a distributed lockstep run reproduces `netmc sim` bit
// for bit. Only simulated drives run in virtual time: hardware needs --clock realtime.
// See docs/architecture.md, "One cycle through the code".

#include <atomic>
#include <map>

#include "server/axis/axis_node_link.hpp"
#include "server/axis/pending_job_starts.hpp"

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
  void reset_faults(const std::vector<std::string>& axes);
  void report_fault(const std::string& axis_name, JobAxis& axis, const std::string& server, std::uint32_t iteration);
  void report_drive(const std::string& axis_name);
  // A job this node cannot run: said, and the axis stays ready.
  void refuse_start(const netmc::dds::JobControl& control, const std::string& why);
  // The pending starts whose server reads now (started) or whose time is over (refused).
  void settle_starts();

  AxisNodeLink link_;
  std::map<std::string, JobAxis> axes_;
  // Each axis's simulated drive of its last job: what its status shows between jobs.
  std::map<std::string, std::shared_ptr<drive::Drive>> drives_;
  PendingJobStarts starts_;
};

}  // namespace netmc::axis
