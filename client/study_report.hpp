#pragma once
// Human and machine outputs of a study: the comparison table, the JSON results and the
// per-cycle CSV traces. Files are written whole or not at all (temporary file, then rename).

#include <CLI/CLI.hpp>

#include <iosfwd>
#include <string>
#include <vector>

#include "client/exclusive_file.hpp"
#include "client/study_plan.hpp"
#include "client/study_runner.hpp"

namespace netmc::cli {

void print_study_table(std::ostream& out, const StudyPlan& plan,
                       const std::vector<RunOutcome>& outcomes);
void print_learning_curve(std::ostream& out, const std::vector<RunOutcome>& outcomes);

// --fail-on-unstable's exit code: a run whose last iteration diverged or did not follow the
// reference (no result), for scripts that must not take a table of failures for success.
inline constexpr int kUnstableExitCode = 3;
// The labels of those runs, in order; empty when every run gave a result.
std::vector<std::string> unstable_runs(const std::vector<RunOutcome>& outcomes);
// Adds --fail-on-unstable to `command`; `exit_code` then maps a study's outcomes to its exit code
// (kUnstableExitCode naming the runs on stderr, else 0).
struct FailOnUnstable {
  bool enabled = false;
  void add_flag(CLI::App* command);
  int exit_code(const std::vector<RunOutcome>& outcomes) const;
};

std::string study_json(const std::vector<RunOutcome>& outcomes);
// Columns: time, per-axis reference/position/measurement, contour errors, commands, loop delay,
// then one column per controller estimate, named NAME[UNIT] (e.g. M1_hat[V/(m/s^2)]).
std::string trace_csv(const std::vector<sim::CycleTrace>& trace,
                      const std::vector<control::EstimateName>& estimate_names = {});
// The same columns as numbers (full precision), for the Python package's Study.trace.
struct TraceColumn {
  std::string name;
  std::vector<double> values;
};
std::vector<TraceColumn> trace_columns(const std::vector<sim::CycleTrace>& trace,
                                       const std::vector<control::EstimateName>& estimate_names = {});

// Before a long run: throws std::invalid_argument("<flag>: ...") when `path` cannot be
// created because its directory is missing or not writable.
void check_output_path(const std::string& path, const std::string& flag);
// A directory an output goes into: an existing, writable one, or one whose parent is.
void check_output_directory(const std::string& directory, const std::string& flag);
// "-" names standard output (then the report a command prints goes to standard error).
bool is_standard_output(const std::string& path);
// Writes `content` to `path` atomically (write_file_atomically), or to standard output for "-".
void write_output(const std::string& path, const std::string& content);
// One CSV per run: DIR/<index>-<controller>.csv; the directory is created if needed.
// The trace file of run `index` (0-based): "<index + 1>-<label>.csv" with every character of the
// label outside A-Z a-z 0-9 . - _ replaced by _ and at most 64 of them, so a label (from a spec
// or a results file) cannot name a path.
std::string trace_file_name(std::size_t index, const std::string& label);
void write_trace_directory(const std::string& directory, const std::vector<RunOutcome>& outcomes);

}  // namespace netmc::cli
