#pragma once
// A sweep split over machines: `netmc sweep --shard K/N` runs the K-th of N interleaved parts of
// a grid (configurations K, K+N, K+2N, ...) and writes part files; `netmc sweep merge PART...`
// joins them into exactly what the unsharded sweep writes. A part names its grid by a
// fingerprint of every configuration's spec, so parts of different grids never mix.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "client/sweep_grid.hpp"

namespace netmc::cli {

struct SweepShard {
  std::size_t index = 1;  // K, 1-based
  std::size_t count = 1;  // N
  bool contains(std::size_t configuration_number) const {
    return (configuration_number - 1) % count == index - 1;
  }
};

// "K/N" with 1 <= K <= N <= 100000; throws std::invalid_argument naming `flag`.
SweepShard parse_sweep_shard(const std::string& text, const std::string& flag);

// 16 hex digits over every configuration (number, base, run, delay bound, seed, job spec).
std::string sweep_grid_fingerprint(const std::vector<SweepConfiguration>& grid);

// The part file's own lines around the unsharded outputs: a CSV part starts with
// "# netmc sweep part K/N grid=FINGERPRINT configurations=C"; a JSON part has a "part" object
// before "configurations".
std::string sweep_csv_part(const SweepShard& shard, const std::string& fingerprint,
                           std::size_t configurations, const std::string& csv);
std::string sweep_json_part(const SweepShard& shard, const std::string& fingerprint,
                            std::size_t configurations, const std::string& json);

// `parts`: (file name, content). All CSV parts or all JSON parts of one grid, each K of 1..N
// exactly once; returns the unsharded file. Throws std::invalid_argument naming the file (and
// the missing or repeated part, or the other grid).
std::string merge_sweep_parts(const std::vector<std::pair<std::string, std::string>>& parts);

// Reads a part file (at most 1 GiB), throwing std::invalid_argument naming it.
std::string read_sweep_part(const std::string& path);

}  // namespace netmc::cli
