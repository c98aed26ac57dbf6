#pragma once
// `netmc sim`: the in-process study in virtual time. Its flags and its work are apart from the
// command line so that the Python package (python/) parses the same flags and runs the same study.

#include <CLI/CLI.hpp>

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "client/study_plan.hpp"
#include "client/study_flags.hpp"
#include "client/study_report.hpp"
#include "client/study_runner.hpp"

namespace netmc::cli {

struct SimFlags {
  StudyFlags study;
  std::string csv_dir;
  std::string plot_dir;
  std::string plot_format = "png,svg";
  unsigned threads = 0;
  bool print_spec = false;
  bool list_presets = false;
  bool list_controllers = false;
  bool list_plants = false;
  bool list_compensators = false;
  std::string plant_parameters;
  FailOnUnstable fail_on_unstable;
};

// Registers `sim` and its flags under `app`.
CLI::App* add_sim_flags(CLI::App& app, SimFlags& flags);

struct SimStudy {
  StudyPlan plan;
  std::vector<RunOutcome> outcomes;
  std::string json;  // what --json writes (empty unless asked for or kept)
};

// What `netmc sim` does with its parsed flags: a listing (printed on standard output; nullopt),
// or the study run, its files written as the flags ask and its table printed on `report`.
// `traces`: at least what the flags need; `keep_json`: render the JSON even without --json.
std::optional<SimStudy> run_sim(const SimFlags& flags, std::ostream& report, TraceRecording traces,
                                bool keep_json);

// Registers the subcommand and its flags; the returned callback runs it (exit code).
std::function<int()> add_sim_command(CLI::App& app);

}  // namespace netmc::cli
