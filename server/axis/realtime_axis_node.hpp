#pragma once
// netmc-axis in realtime mode: the axis samples on a Boost.Asio steady timer every period and
// applies each setpoint when it arrives (real DDS latency plus the downlink netsim delay),
// through the same AxisEndpoint as the simulation. Times are job times on CLOCK_MONOTONIC,
// shared by every process on a host (and by network namespaces of one machine).

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
  void serve(const std::atomic<bool>& stop);

 private:
  struct OwnedAxis : JobAxis {
    std::uint32_t iteration = 0;
    double start_monotonic_s = 0.0;
    std::uint64_t next_cycle = 0;
    double last_setpoint_s = 0.0;   // job time of the last setpoint received
    bool holding = false;
    // Server departure time of each setpoint in flight: tau_ca then includes the real DDS
    // latency, not only the emulated part that starts when the sample reaches this node.
    std::map<std::uint64_t, double> server_send_times;
    std::unique_ptr<boost::asio::steady_timer> timer;
  };

  void handle(const netmc::dds::Setpoint& setpoint);
  void tick(std::uint32_t axis_id);
  void schedule(OwnedAxis& axis, std::uint32_t axis_id);
  void publish_final(std::uint32_t axis_id, OwnedAxis& axis);

  boost::asio::io_context io_;
  AxisNodeLink link_;
  std::chrono::milliseconds watchdog_;
  std::map<std::uint32_t, OwnedAxis> axes_;
};

// CLOCK_MONOTONIC in seconds (std::chrono::steady_clock on Linux).
double monotonic_now_s();

}  // namespace netmc::axis
