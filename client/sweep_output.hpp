#pragma once
// Outputs of `netmc sweep`: a tidy CSV (one row per configuration x iteration, every metric of
// IterationMetrics as a unit-suffixed column), the same as JSON, and a summary table.

#include <iosfwd>
#include <string>
#include <vector>

#include "client/study_runner.hpp"
#include "client/sweep_grid.hpp"

namespace netmc::cli {

// Column names: configuration columns, then every IterationMetrics field (per-axis fields
// split into _x/_y (and _z for `axes` = 3) before the unit suffix: tracking_rms_x_m).
std::vector<std::string> sweep_csv_columns(std::size_t axes = 2);
// `outcomes[i]` belongs to `grid[i]`.
std::string sweep_csv(const std::vector<SweepConfiguration>& grid,
                      const std::vector<RunOutcome>& outcomes);
std::string sweep_json(const std::vector<SweepConfiguration>& grid,
                       const std::vector<RunOutcome>& outcomes);
// Last iteration, mean over seeds: one row per (base, delay upper bound), one column per run.
void print_sweep_summary(std::ostream& out, const std::vector<SweepConfiguration>& grid,
                         const std::vector<RunOutcome>& outcomes);

}  // namespace netmc::cli
