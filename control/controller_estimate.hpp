#pragma once
// An internal estimate of a controller, named with its unit: an adaptive parameter (DIARC's M1_hat),
// an observer state (ADRC's total disturbance), a data model's Phi_hat. The job runner records
// their values per cycle (--csv traces) and at the end of each iteration (--json).

#include <cstddef>
#include <string>

namespace netmc::control {

struct EstimateName {
  std::string name;  // e.g. "M1_hat"
  std::string unit;  // e.g. "V/(m/s^2)"
};

// Most estimates a controller may expose (the trace rows keep a fixed-size array of them).
inline constexpr std::size_t kMaxControllerEstimates = 24;

}  // namespace netmc::control
