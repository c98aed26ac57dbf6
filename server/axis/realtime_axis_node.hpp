#pragma once
// netmc-axis in realtime mode: every axis samples once a period on the node's own clock and
// applies each setpoint when it arrives (real DDS latency plus the downlink netsim delay),
// through the same AxisEndpoint as the simulation. Times are job times on the node's own clock
// (its --time-base): the server sends each iteration's start already converted to this clock
// with the offset it measured, so no clock is shared between hosts.
//
// One thread does it all: it sleeps on a DDS WaitSet until the next sample is due, so a
// setpoint goes from Fast DDS's receive thread to the actuator in one wake-up, and the samples
// of all the node's axes are taken back to back.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

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
  using Clock = std::chrono::steady_clock;

  struct OwnedAxis : JobAxis {
    std::string server;
    std::uint32_t iteration = 0;
    double start_time_s = 0.0;       // t = 0 of the iteration on this node's clock
    std::uint64_t next_cycle = 0;
    Clock::time_point next_sample;   // when cycle next_cycle is due (running)
    Clock::time_point report_at;     // when the iteration's report goes out (ending)
    std::uint64_t commands_sent = 0; // by the server, from END_ITERATION
    double last_setpoint_s = 0.0;    // job time of the last setpoint received
    bool holding = false;
    bool running = false;            // sampling (between BEGIN and END_ITERATION)
    bool ending = false;             // END_ITERATION came; the report waits for late setpoints
    std::uint64_t samples = 0;
    std::uint64_t commands_received = 0;
    // Server departure time of each setpoint in flight: tau_ca then includes the real DDS
    // latency, not only the emulated part that starts when the sample reaches this node.
    std::map<std::uint64_t, double> server_send_times;
    // Round trip of the loop on this node's clock: feedback k written -> setpoint k in. By
    // cycle, sized once per iteration (nothing allocated in a cycle); a setpoint older than the
    // newest one timed is not timed.
    std::vector<Clock::time_point> feedback_sent;
    std::int64_t newest_timed = -1;
    std::vector<double> round_trips_s;
    std::vector<double> wake_late_s;  // how late each sample was taken after its due time
  };

  void handle(const netmc::dds::JobControl& control);
  void handle(const netmc::dds::Setpoint& setpoint);
  void sample(const std::string& axis_name, OwnedAxis& axis, Clock::time_point now);
  void end_iteration(const std::string& axis_name, OwnedAxis& axis);
  void schedule(OwnedAxis& axis) const;
  // Samples are due until the iteration's last; setpoints are taken until END_ITERATION.
  static bool sampling(const OwnedAxis& axis) {
    return axis.running && axis.endpoint && axis.next_cycle < axis.cycles;
  }
  void publish_status();

  AxisNodeLink link_;
  std::chrono::milliseconds watchdog_;
  std::map<std::string, OwnedAxis> axes_;
};

}  // namespace netmc::axis
