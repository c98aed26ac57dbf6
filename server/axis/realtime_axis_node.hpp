#pragma once
// netmc-axis in realtime mode: the axis samples on a Boost.Asio steady timer every period and
// applies each setpoint when it arrives (real DDS latency plus the downlink netsim delay),
// through the same AxisEndpoint as the simulation. Times are job times on the node's own clock
// (its --time-base): the server sends each iteration's start already converted to this clock
// with the offset it measured, so no clock is shared between hosts.

#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio.hpp>

#include <atomic>
#include <map>
#include <memory>

#include "dds_types.h"
#include "server/axis/axis_node_link.hpp"

namespace netmc::axis {

class RealtimeAxisNode {
 public:
  RealtimeAxisNode(dds::DdsContext& context, AxisNodeConfig config,
                   std::chrono::milliseconds watchdog);
  AxisNodeLink& link() { return link_; }
  void serve(const std::atomic<bool>& stop);

 private:
  struct OwnedAxis : JobAxis {
    std::string server;
    std::uint32_t iteration = 0;
    double start_time_s = 0.0;       // t = 0 of the iteration on this node's clock
    std::uint64_t next_cycle = 0;
    double last_setpoint_s = 0.0;    // job time of the last setpoint received
    bool holding = false;
    bool running = false;            // sampling (between BEGIN and END_ITERATION)
    bool ending = false;             // END_ITERATION came; the report waits for late setpoints
    std::uint64_t samples = 0;
    std::uint64_t commands_received = 0;
    // Server departure time of each setpoint in flight: tau_ca then includes the real DDS
    // latency, not only the emulated part that starts when the sample reaches this node.
    std::map<std::uint64_t, double> server_send_times;
    std::unique_ptr<boost::asio::steady_timer> timer;
  };

  void handle(const netmc::dds::JobControl& control);
  void handle(const netmc::dds::Setpoint& setpoint);
  void tick(const std::string& axis_name);
  void schedule(OwnedAxis& axis, const std::string& axis_name);
  void end_iteration(const std::string& axis_name, OwnedAxis& axis, std::uint64_t commands_sent);

  boost::asio::io_context io_;
  AxisNodeLink link_;
  std::chrono::milliseconds watchdog_;
  std::map<std::string, OwnedAxis> axes_;
};

}  // namespace netmc::axis
