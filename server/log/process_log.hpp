#pragma once
// The log of netmc-server and netmc-axis: one levelled, timestamped line per event on standard
// error (spdlog), e.g.
//   2026-11-25 14:20:01.123 info  netmc-server: job 3 running on axes x,y (1 running, 0 queued)
// Call sites use spdlog::info / warn / error; init sets the pattern once the process knows its
// name ("netmc-server", "netmc-axis NODE").

#include <string>

namespace netmc::log {

void init(const std::string& program);

}  // namespace netmc::log
