#pragma once
// What a live view of a job sees of each computed cycle (netmc-server's console). The control
// loop calls on_cycle() right after it computes a cycle: an implementation must return at once,
// whatever its reader does (drop rather than wait), and never throw.

#include <cstddef>
#include <cstdint>

#include "control/group/contour_group.hpp"

namespace netmc::sim {

struct LiveCycle {
  std::size_t iteration = 0;
  std::uint64_t cycle = 0;
  double time_s = 0.0;
  control::AxisVector reference_m;
  control::AxisVector position_m;     // the axes' true positions as reported
  double contour_error_m = 0.0;
  control::AxisVector command;        // as sent, per axis
  double latest_tau_s = -1.0;         // the newest loop delay measured on axis 0 (-1: none yet)
};

class CycleListener {
 public:
  virtual ~CycleListener() = default;
  virtual void on_cycle(const LiveCycle& cycle) noexcept = 0;
};

}  // namespace netmc::sim
