#pragma once
// Independent random streams per link, axis and iteration, all derived from the job seed, so
// that the in-process run and a distributed lockstep run draw exactly the same numbers.

#include <cstddef>
#include <cstdint>

#include "netsim/random_stream.hpp"

namespace netmc::sim {

enum class StreamKind : std::uint64_t { uplink = 1, downlink = 2, sensor = 3 };

inline std::uint64_t stream_id(StreamKind kind, std::size_t axis, std::size_t iteration) {
  return (static_cast<std::uint64_t>(iteration) << 16) | (static_cast<std::uint64_t>(axis) << 8) |
         static_cast<std::uint64_t>(kind);
}

inline netsim::RandomStream job_stream(std::uint64_t seed, StreamKind kind, std::size_t axis,
                                       std::size_t iteration) {
  return netsim::RandomStream(seed, stream_id(kind, axis, iteration));
}

}  // namespace netmc::sim
