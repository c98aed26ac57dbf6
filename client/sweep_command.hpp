#pragma once
// `netmc sweep`: a grid of studies (base x controller x delay x seed) run in-process on all
// cores (or on a netmc-server), written as a tidy CSV and JSON once everything has run; with
// --shard K/N one part of the grid, and `netmc sweep merge` joins the parts. Flags and work are
// apart from the command line so that the Python package runs the same grid from the same flags.

#include <CLI/CLI.hpp>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "client/sweep_grid.hpp"

namespace netmc::cli {

struct SweepFlags {
  SweepAxes axes;
  std::string presets;
  std::string csv_path, json_path, server, plot_dir, shard;
  unsigned threads = 0;
  std::vector<std::string> merge_parts;
  std::string merge_output = "-";
};

struct SweepCommand {
  CLI::App* sweep = nullptr;
  CLI::App* merge = nullptr;
};
// Registers `sweep` (and `sweep merge`) and their flags under `app`.
SweepCommand add_sweep_flags(CLI::App& app, SweepFlags& flags);

struct SweepRunOptions {
  bool keep_csv = false;         // render the CSV even without --csv (a part's, with --shard)
  bool keep_json = false;
  bool progress = true;          // the progress bar on standard error
  std::ostream* report = nullptr;  // the summary; default standard output (error when piped)
};

struct SweepStudy {
  std::string csv, json;         // as written (a part file's text with --shard)
  std::size_t configurations = 0;  // run here
  std::size_t grid_configurations = 0;  // in the whole grid
};

// The grid the flags describe, in grid order (nothing run).
std::vector<SweepConfiguration> expand_sweep_flags(const SweepFlags& flags);
// What `netmc sweep` does with its parsed flags: the grid (or its shard) run, the files written
// as the flags ask, the summary printed. Throws std::invalid_argument naming the flag.
SweepStudy run_sweep(const SweepFlags& flags, const SweepRunOptions& options);
// `netmc sweep merge`: the joined text, also written to --output.
std::string run_sweep_merge(const SweepFlags& flags);

std::function<int()> add_sweep_command(CLI::App& app);

}  // namespace netmc::cli
