#pragma once
// GoogleTest prints a PowerState by its name (found by argument-dependent lookup).
#include <ostream>

#include "server/drive/cia402.hpp"

namespace netmc::drive {
inline void PrintTo(PowerState state, std::ostream* out) { *out << power_state_name(state); }
}  // namespace netmc::drive
