#pragma once
// The grid of `netmc sweep`: base studies (presets, trajectories) x runs (controllers) x loop
// delays x seeds, expanded into one JobSpec per configuration in a fixed order, so that the
// configuration numbers and results do not depend on how the grid is run.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "client/spec_syntax.hpp"
#include "client/study_flags.hpp"

namespace netmc::cli {

struct SweepAxes {
  std::vector<std::string> presets;        // --preset a,b; empty: seed001
  std::vector<std::string> trajectories;   // --trajectory (repeatable); empty: each preset's own
  std::string controllers;                 // --controller a,b; empty: the runs of each preset
  std::vector<std::string> delays;         // --delay (repeatable): whole delay specs
  std::string delay_max;                   // --delay-max 0.5ms:10ms:20 | 1ms,2ms: uniform upper bounds
  std::string delay_min;                   // --delay-min: lower bound with --delay-max (default 0.3ms)
  std::string seeds;                       // --seeds 1..5 | 1,4,9
  StudyFlags fixed;                        // applied to every job (plant, gains, iterations ...)
};

struct SweepConfiguration {
  std::size_t number = 0;                  // 1-based, in grid order
  std::string base;                        // preset, or preset/trajectory
  std::string label;                       // the run: its controller or its name
  std::optional<double> delay_max_s;       // the loop delay's upper bound, when it has one
  std::uint64_t seed = 0;
  netmc::v1::JobSpec job;
};

// "0.5ms:10ms:20" (start:stop:count, evenly spaced, both ends included) or "1ms,2ms,5ms".
// Throws std::invalid_argument naming `flag` and the expected form.
std::vector<double> parse_value_axis(const std::string& text, Quantity quantity,
                                     std::string_view flag);
// "1..5" (inclusive) or "1,4,9".
std::vector<std::uint64_t> parse_seed_axis(const std::string& text);
// The upper bound of a delay profile (constant, uniform, truncated normal/pareto, markov, none).
std::optional<double> delay_upper_bound_s(const netmc::v1::DelayProfile& delay);

// Grid order: base, run, delay, seed (the last varies fastest).
std::vector<SweepConfiguration> expand_sweep(const SweepAxes& axes);

}  // namespace netmc::cli
