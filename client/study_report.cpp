#include "client/study_report.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

#include "plant/plant_catalog.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::cli {
namespace {

const netmc::v1::IterationMetrics& last(const RunOutcome& outcome) {
  return outcome.result.iterations(outcome.result.iterations_size() - 1);
}

// The paper's row for a run: the one named like the run (e.g. "gtcf-sarc (D)"), else the one
// of its controller.
const PaperRow* paper_row(const StudyPlan& plan, const netmc::v1::RunResult& run) {
  for (const std::string* key : {&run.label(), &run.controller()}) {
    for (const auto& row : plan.paper) {
      if (row.controller == *key) return &row;
    }
  }
  return nullptr;
}

}  // namespace

namespace {

bool trajectories_differ(const std::vector<RunOutcome>& outcomes) {
  return std::any_of(outcomes.begin(), outcomes.end(), [&](const RunOutcome& o) {
    return o.result.trajectory() != outcomes.front().result.trajectory();
  });
}

// The first run on the same trajectory as `outcome`: what its rms/first compares with.
const RunOutcome& first_on_trajectory(const std::vector<RunOutcome>& outcomes, const RunOutcome& outcome) {
  return *std::find_if(outcomes.begin(), outcomes.end(), [&](const RunOutcome& o) {
    return o.result.trajectory() == outcome.result.trajectory();
  });
}

// The input unit of a run's plant ("ballscrew (y: load_kg=3)" names the plant first).
std::string input_unit(const std::string& plant_description) {
  try {
    return plant::plant_input_unit(plant_description.substr(0, plant_description.find(' ')));
  } catch (const std::invalid_argument&) {
    return "input unit";
  }
}

// A run whose axes did not follow the reference has no contour error worth a number (an axis
// standing on a closed curve has none): say so, with the tracking error that shows it.
std::string not_following(const netmc::v1::IterationMetrics& m) {
  double tracking_max_m = 0.0;
  for (const double value : m.tracking_max_m()) tracking_max_m = std::max(tracking_max_m, value);
  return fmt::format("did not follow the reference: an axis covered less than half of its path (tracking "
                     "error up to {:.3f} mm); its contour error is no result",
                     tracking_max_m * 1e3);
}

// A paper value in um, or "-" where the paper gives none (NaN).
std::string paper_micrometres(double metres) {
  return std::isfinite(metres) ? fmt::format("{:.2f}", metres * 1e6) : std::string("-");
}

// Studies judged after the start-up transient (thesis): steady RMS and max in um, inputs in the
// plant's unit.
void print_steady_table(std::ostream& out, const StudyPlan& plan,
                        const std::vector<RunOutcome>& outcomes) {
  std::size_t width = 18;
  for (const auto& outcome : outcomes) width = std::max(width, outcome.result.label().size());
  const std::string unit = input_unit(outcomes.front().result.plant());
  fmt::print(out, "{:<{}} {:>17} {:>17} {:>10}  {:>11} {:>11}  {:>16} {:>16}\n", "run", width,
             "e_rms_steady [um]", "e_max_steady [um]", "rms/first", "u_x rms [" + unit + "]",
             "u_y rms [" + unit + "]", "paper rms [um]", "paper max [um]");
  for (const auto& outcome : outcomes) {
    const auto& m = last(outcome);
    const auto& first = last(first_on_trajectory(outcomes, outcome));
    if (m.has_stop_reason()) {
      fmt::print(out, "{:<{}} stopped: {}\n", outcome.result.label(), width, m.stop_reason());
      continue;
    }
    if (m.diverged()) {
      fmt::print(out, "{:<{}} unstable at t = {:.3f} s\n", outcome.result.label(), width, m.diverged_at_s());
      continue;
    }
    if (m.did_not_follow()) {
      fmt::print(out, "{:<{}} {}\n", outcome.result.label(), width, not_following(m));
      continue;
    }
    if (!m.has_e_rms_steady_m()) {  // no sample in the window
      fmt::print(out, "{:<{}} no steady metrics: the run ends before its evaluation window (t >= {:g} s)\n",
                 outcome.result.label(), width, outcome.result.evaluation_start_s());
      continue;
    }
    // A one-axis run has no u_y.
    const auto input = [&](int axis) {
      return axis < m.command_rms_steady_size() ? fmt::format("{:.2f}", m.command_rms_steady(axis)) : std::string("-");
    };
    fmt::print(out, "{:<{}} {:>17.2f} {:>17.2f} {:>10.3f}  {:>11} {:>11}", outcome.result.label(), width,
               m.e_rms_steady_m() * 1e6, m.e_max_steady_m() * 1e6,
               first.e_rms_steady_m() > 0.0 ? m.e_rms_steady_m() / first.e_rms_steady_m() : std::numeric_limits<double>::quiet_NaN(), input(0), input(1));
    if (const PaperRow* row = paper_row(plan, outcome.result)) {
      fmt::print(out, "  {:>16} {:>16}", paper_micrometres(row->e_max_m), paper_micrometres(row->e_sum_m));
    }
    fmt::print(out, "\n");
  }
  if (trajectories_differ(outcomes)) {
    fmt::print(out, "\nrms/first: against the first run on the same trajectory; trajectories:\n");
    for (const auto& outcome : outcomes) {
      if (&first_on_trajectory(outcomes, outcome) != &outcome) continue;
      fmt::print(out, "  from {}: {}\n", outcome.result.label(), outcome.result.trajectory());
    }
  }
}

bool delays_differ(const std::vector<RunOutcome>& outcomes) {
  return std::any_of(outcomes.begin(), outcomes.end(), [&](const RunOutcome& o) {
    return o.result.delay() != outcomes.front().result.delay();
  });
}

// A sweep over loop delays: one row per run label, one column per delay, steady RMS / max (um).
void print_steady_sweep(std::ostream& out, const std::vector<RunOutcome>& outcomes) {
  std::vector<std::string> labels, delays;
  for (const auto& o : outcomes) {
    if (std::find(labels.begin(), labels.end(), o.result.label()) == labels.end()) labels.push_back(o.result.label());
    if (std::find(delays.begin(), delays.end(), o.result.delay()) == delays.end()) delays.push_back(o.result.delay());
  }
  std::size_t width = 3;
  for (const auto& label : labels) width = std::max(width, label.size());
  fmt::print(out, "steady contour error RMS / max [um] by loop delay (downlink)\n{:<{}}", "run", width);
  for (const auto& delay : delays) fmt::print(out, " {:>24}", delay);
  fmt::print(out, "\n");
  for (const auto& label : labels) {
    fmt::print(out, "{:<{}}", label, width);
    for (const auto& delay : delays) {
      const auto found = std::find_if(outcomes.begin(), outcomes.end(), [&](const RunOutcome& o) {
        return o.result.label() == label && o.result.delay() == delay;
      });
      std::string cell = "-";
      if (found != outcomes.end()) {
        const auto& m = last(*found);
        cell = m.diverged()                ? fmt::format("unstable at {:.2f} s", m.diverged_at_s())
               : m.did_not_follow()        ? std::string("did not follow")
               : !m.has_e_rms_steady_m()   ? std::string("no steady window")
                                           : fmt::format("{:.2f} / {:.2f}", m.e_rms_steady_m() * 1e6, m.e_max_steady_m() * 1e6);
      }
      fmt::print(out, " {:>24}", cell);
    }
    fmt::print(out, "\n");
  }
}

}  // namespace

void print_study_table(std::ostream& out, const StudyPlan& plan,
                       const std::vector<RunOutcome>& outcomes) {
  if (outcomes.empty()) return;
  if (plan.steady_metrics) {
    const auto& first = outcomes.front().result;
    const bool sweep = delays_differ(outcomes);
    fmt::print(out, "{}\ntrajectory {} | plant {} | delay {} | h = {:.6g} ms | seed {}\n\n", plan.title,
               !sweep && trajectories_differ(outcomes) ? std::string("by run (below)") : first.trajectory(), first.plant(),
               sweep ? "by column" : first.delay(),
               first.sample_period_s() * 1e3, first.seed());
    if (sweep) {
      print_steady_sweep(out, outcomes);
    } else {
      print_steady_table(out, plan, outcomes);
    }
    return;
  }
  const auto& first = outcomes.front().result;
  fmt::print(out, "{}\n", plan.title);
  fmt::print(out, "trajectory {} | plant {} | delay {} | h = {:.6g} ms | {} iterations | seed {}\n\n",
             first.trajectory(), first.plant(), first.delay(), first.sample_period_s() * 1e3,
             first.iterations_size(), first.seed());
  const bool with_paper = !plan.paper.empty();
  fmt::print(out, "{:<18} {:>11} {:>11} {:>11} {:>9} {:>9}  {:>22}", "run", "e_max [mm]",
             "e_sum [mm]", "e_rms [um]", "e_max/ref", "e_sum/ref", "tau mean/p99/max [ms]");
  if (with_paper) fmt::print(out, "  {:>12} {:>12}", "paper e_max", "paper e_sum");
  fmt::print(out, "\n");
  const auto& reference = last(outcomes.front());
  for (const auto& outcome : outcomes) {
    const auto& m = last(outcome);
    if (m.has_stop_reason()) {
      fmt::print(out, "{:<18} stopped: {} of iteration {}\n", outcome.result.label(), m.stop_reason(), m.iteration());
      continue;
    }
    if (m.diverged()) {
      fmt::print(out, "{:<18} unstable: contour error beyond the divergence limit at t = {:.3f} s of iteration {}\n",
                 outcome.result.label(), m.diverged_at_s(), m.iteration());
      continue;
    }
    if (m.did_not_follow()) {
      fmt::print(out, "{:<18} {}\n", outcome.result.label(), not_following(m));
      continue;
    }
    fmt::print(out, "{:<18} {:>11.4f} {:>11.3f} {:>11.2f} {:>9.3f} {:>9.3f}  {:>6.3f}/{:>6.3f}/{:>6.3f}",
               outcome.result.label(), m.e_max_m() * 1e3, m.e_sum_m() * 1e3,
               m.e_rms_m() * 1e6, m.e_max_m() / reference.e_max_m(),
               m.e_sum_m() / reference.e_sum_m(), m.tau_mean_s() * 1e3, m.tau_p99_s() * 1e3,
               m.tau_max_s() * 1e3);
    if (with_paper) {
      if (const PaperRow* row = paper_row(plan, outcome.result)) {
        fmt::print(out, "  {:>12.4f} {:>12.4f}", row->e_max_m * 1e3, row->e_sum_m * 1e3);
      }
    }
    fmt::print(out, "\n");
  }
  fmt::print(out, "\nlast iteration of each run; ratios against the first row ({})", outcomes.front().result.label());
  if (with_paper) {
    const auto* adrc = paper_row(plan, outcomes.front().result);
    const auto* best = &plan.paper.back();
    if (adrc && adrc == &plan.paper.front()) {
      fmt::print(out, "; {}: {} e_max/ref {:.3f}, e_sum/ref {:.3f}", plan.paper_source,
                 best->controller, best->e_max_m / adrc->e_max_m, best->e_sum_m / adrc->e_sum_m);
    }
  }
  fmt::print(out, "\n");
}

void print_learning_curve(std::ostream& out, const std::vector<RunOutcome>& outcomes) {
  for (const auto& outcome : outcomes) {
    if (outcome.result.iterations_size() < 2) continue;
    fmt::print(out, "\n{}: e_sum [mm] by iteration\n", outcome.result.label());
    for (const auto& m : outcome.result.iterations()) {
      fmt::print(out, "  {:>3}  e_sum {:>9.3f}  e_max {:>8.4f}\n", m.iteration(),
                 m.e_sum_m() * 1e3, m.e_max_m() * 1e3);
    }
  }
}

std::string study_json(const std::vector<RunOutcome>& outcomes) {
  netmc::v1::StudyResult study;
  for (const auto& outcome : outcomes) *study.add_runs() = outcome.result;
  return job::to_json(study);
}

std::vector<std::string> trace_column_names(std::size_t axes, const std::vector<control::EstimateName>& estimate_names) {
  // Columns per axis of the group, named by the contour's coordinates x, y (, z).
  std::vector<std::string> names{"time_s"};
  const auto columns = [&](const char* prefix, const char* suffix) {
    for (std::size_t i = 0; i < axes; ++i) {
      names.push_back(i < 3 ? fmt::format("{}{}{}", prefix, "xyz"[i], suffix) : fmt::format("{}q{}{}", prefix, i + 1, suffix));
    }
  };
  columns("", "_ref_m");
  columns("", "_m");
  columns("", "_measured_m");
  names.insert(names.end(), {"contour_error_m", "contour_error_estimate_m"});
  columns("u", "");
  columns("U", "");
  names.insert(names.end(), {"ue", "tau_x_s"});
  const std::size_t estimates = std::min(estimate_names.size(), control::kMaxControllerEstimates);
  for (std::size_t i = 0; i < estimates; ++i) {
    names.push_back(fmt::format("{}[{}]", estimate_names[i].name, estimate_names[i].unit));
  }
  return names;
}

std::vector<TraceColumn> trace_columns(const std::vector<sim::CycleTrace>& trace,
                                       const std::vector<control::EstimateName>& estimate_names) {
  const std::size_t axes = trace.empty() ? 2 : static_cast<std::size_t>(trace.front().position_m.size());
  const auto names = trace_column_names(axes, estimate_names);
  std::vector<TraceColumn> columns(names.size());
  for (std::size_t c = 0; c < names.size(); ++c) {
    columns[c].name = names[c];
    columns[c].values.reserve(trace.size());
  }
  for (const auto& row : trace) {
    std::size_t c = 0;
    columns[c++].values.push_back(row.time_s);
    for (const auto* v : {&row.reference_m, &row.position_m, &row.measured_m}) {
      for (std::size_t i = 0; i < axes; ++i) columns[c++].values.push_back((*v)[static_cast<Eigen::Index>(i)]);
    }
    columns[c++].values.push_back(row.contour_error_m);
    columns[c++].values.push_back(row.contour_error_estimate_m);
    for (const auto* v : {&row.axis_command, &row.command}) {
      for (std::size_t i = 0; i < axes; ++i) columns[c++].values.push_back((*v)[static_cast<Eigen::Index>(i)]);
    }
    columns[c++].values.push_back(row.coupling_command);
    columns[c++].values.push_back(row.tau_s);
    for (std::size_t i = 0; c < columns.size(); ++i) columns[c++].values.push_back(row.estimates[i]);
  }
  return columns;
}

std::string trace_csv(const std::vector<sim::CycleTrace>& trace,
                      const std::vector<control::EstimateName>& estimate_names) {
  const std::size_t axes = trace.empty() ? 2 : static_cast<std::size_t>(trace.front().position_m.size());
  const std::size_t estimates = std::min(estimate_names.size(), control::kMaxControllerEstimates);
  std::string csv;
  for (const auto& name : trace_column_names(axes, estimate_names)) {
    if (!csv.empty()) csv += ',';
    csv += name;
  }
  csv += '\n';
  const auto values = [&](const control::AxisVector& v, const char* format) {
    for (std::size_t i = 0; i < axes; ++i) {
      csv += ',';
      csv += fmt::format(fmt::runtime(format), v[static_cast<Eigen::Index>(i)]);
    }
  };
  for (const auto& row : trace) {
    csv += fmt::format("{:.6f}", row.time_s);
    values(row.reference_m, "{:.9e}");
    values(row.position_m, "{:.9e}");
    values(row.measured_m, "{:.9e}");
    csv += fmt::format(",{:.6e},{:.6e}", row.contour_error_m, row.contour_error_estimate_m);
    values(row.axis_command, "{:.6e}");
    values(row.command, "{:.6e}");
    csv += fmt::format(",{:.6e},{:.6e}", row.coupling_command, row.tau_s);
    for (std::size_t i = 0; i < estimates; ++i) csv += fmt::format(",{:.9e}", row.estimates[i]);
    csv += '\n';
  }
  return csv;
}

bool is_standard_output(const std::string& path) { return path == "-"; }

void write_output(const std::string& path, const std::string& content) {
  if (!is_standard_output(path)) {
    write_file_atomically(path, content);
    return;
  }
  std::cout << content;
  if (!content.empty() && content.back() != '\n') std::cout << '\n';
  std::cout.flush();
}

void check_output_path(const std::string& path, const std::string& flag) {
  if (is_standard_output(path)) return;
  std::filesystem::path directory = std::filesystem::path(path).parent_path();
  if (directory.empty()) directory = ".";
  if (std::filesystem::is_directory(path)) {
    throw std::invalid_argument(flag + ": '" + path + "' is a directory (expected a file name)");
  }
  if (!std::filesystem::is_directory(directory)) {
    throw std::invalid_argument(flag + ": directory '" + directory.string() + "' does not exist");
  }
  if (access(directory.c_str(), W_OK) != 0) {
    throw std::invalid_argument(flag + ": directory '" + directory.string() + "' is not writable");
  }
}

void check_output_directory(const std::string& directory, const std::string& flag) {
  if (std::filesystem::exists(directory)) {
    if (!std::filesystem::is_directory(directory)) {
      throw std::invalid_argument(flag + ": '" + directory + "' is not a directory");
    }
    if (access(directory.c_str(), W_OK) != 0) {
      throw std::invalid_argument(flag + ": directory '" + directory + "' is not writable");
    }
    return;
  }
  check_output_path(directory, flag);  // made when written: its parent must take it
}

std::string trace_file_name(std::size_t index, const std::string& label) {
  std::string name = label.substr(0, 64);
  for (char& c : name) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                       c == '-' || c == '_';
    if (!plain) c = '_';
  }
  return fmt::format("{}-{}.csv", index + 1, name);
}

void write_trace_directory(const std::string& directory, const std::vector<RunOutcome>& outcomes) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory)) {
    throw std::runtime_error(directory + ": cannot create the trace directory");
  }
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const auto& outcome = outcomes[i];
    // Every iteration's traces kept (TraceRecording::every_iteration): the last of them.
    const auto& last = outcome.last_trace.empty() && !outcome.iteration_traces.empty() ? outcome.iteration_traces.back()
                                                                                       : outcome.last_trace;
    write_file_atomically((std::filesystem::path(directory) / trace_file_name(i, outcome.result.label())).string(),
                          trace_csv(last, outcome.estimate_names));
  }
}

std::vector<std::string> unstable_runs(const std::vector<RunOutcome>& outcomes) {
  std::vector<std::string> labels;
  for (const auto& outcome : outcomes) {
    const auto& iterations = outcome.result.iterations();
    if (iterations.empty()) continue;
    const auto& last = iterations[iterations.size() - 1];
    if (last.diverged() || last.did_not_follow()) labels.push_back(outcome.result.label());
  }
  return labels;
}

void FailOnUnstable::add_flag(CLI::App* command) {
  command->add_flag("--fail-on-unstable", enabled,
                    "Exit with code 3 when a run's last iteration diverged or did not follow the reference (the "
                    "table and files are written all the same)");
}

int FailOnUnstable::exit_code(const std::vector<RunOutcome>& outcomes) const {
  if (!enabled) return 0;
  const auto labels = unstable_runs(outcomes);
  if (labels.empty()) return 0;
  std::string names;
  for (const auto& label : labels) names += (names.empty() ? "" : ", ") + label;
  fmt::print(stderr, "netmc: {} of {} runs gave no result (unstable or did not follow): {}\n", labels.size(),
             outcomes.size(), names);
  return kUnstableExitCode;
}

}  // namespace netmc::cli
