#include "client/sim_command.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <thread>

#include "client/figures.hpp"
#include "client/plot_command.hpp"
#include "client/study_flags.hpp"
#include "client/study_report.hpp"
#include "client/study_runner.hpp"
#include "plant/plant_registry.hpp"
#include "server/job/controller_registry.hpp"
#include "server/job/delay_compensators.hpp"
#include "server/job/job_builder.hpp"
#include "server/job/plant_source.hpp"

namespace netmc::cli {

CLI::App* add_sim_flags(CLI::App& app, SimFlags& flags) {
  CLI::App* sim = app.add_subcommand("sim", "Run a study in-process, in virtual time (default: --preset seed001)");
  add_study_flags(sim, flags.study);
  sim->add_option("--csv", flags.csv_dir, "Write per-cycle traces of each run's last iteration into DIR");
  sim->add_option("--plot", flags.plot_dir,
                  "Write results.json, traces/ and the standard figures (PNG, SVG) into DIR")
      ->type_name("DIR");
  sim->add_option("--plot-format", flags.plot_format, "Figure formats with --plot: png, svg or png,svg")
      ->type_name("FORMATS");
  sim->add_option("--threads", flags.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  sim->add_flag("--print-spec", flags.print_spec,
                "Print the job spec of the study's first run as JSON (what --spec reads) and run nothing");
  sim->add_flag("--list-presets", flags.list_presets, "Print the names of the presets and run nothing");
  sim->add_flag("--list-controllers", flags.list_controllers,
                "Print every controller netmc runs (a Markdown table: names, role, gains flag, source, the plants "
                "its defaults are tuned for) and run nothing");
  sim->add_flag("--list-plants", flags.list_plants,
                "Print every named plant --plant takes (a Markdown table: name, model, source, input unit, travel, "
                "rated input, parameters) and run nothing");
  sim->add_flag("--list-compensators", flags.list_compensators,
                "Print every delay compensator --compensate takes (a Markdown table: name, what it does, what it "
                "predicts with, source) and run nothing");
  flags.fail_on_unstable.add_flag(sim);
  sim->add_option("--plant-parameters", flags.plant_parameters,
                  "Print the parameters --plant NAME:KEY=VALUE (and a spec's plant_axes) can change, and run nothing")
      ->type_name("NAME");
  sim->footer(R"(Examples:
  netmc sim                                        # paper 001's study (Table 1) and its table
  netmc sim --plot figures                         # ... plus figures/contour.png, contour_error,
                                                   #     e_sum, tau_histogram (.png and .svg)
  netmc sim --iterations 100 --curve               # learning curves
  netmc sim --controller adrc,adrc+pidccc --delay constant:4ms
  netmc sim --controller adrc,adrc+ilccc --delay constant:20ms --compensate predictor
  netmc sim --preset thesis-ellipse
  netmc sim --spec job.json --json results.json --csv traces/

Values are SI unless suffixed (s, ms, us, m, mm, um). Flags override the preset or spec for
every run. Output files are written whole, after every run has finished.)");

  return sim;
}

std::optional<SimStudy> run_sim(const SimFlags& flags, std::ostream& report, TraceRecording traces, bool keep_json) {
  if (!flags.plant_parameters.empty()) {
    const std::string& name = flags.plant_parameters;
    const auto parameters = job::job_plant_parameters(name);  // throws naming the known plants
    fmt::print("{} (input and disturbances in {}):\n", name, job::job_plant_input_unit(name));
    for (const auto& p : parameters) fmt::print("  {:<28} {}\n", p.key, p.description);
    return std::nullopt;
  }
  if (flags.list_controllers) {
    fmt::print("{}", job::ControllerRegistry::global().markdown_table());
    return std::nullopt;
  }
  if (flags.list_plants) {
    fmt::print("{}", plant::PlantRegistry::global().markdown_table());
    return std::nullopt;
  }
  if (flags.list_compensators) {
    fmt::print("{}", job::delay_compensators_markdown_table());
    return std::nullopt;
  }
  if (flags.list_presets) {
    for (const auto& name : preset_names()) fmt::print("{}\n", name);
    return std::nullopt;
  }
  StudyPlan plan = plan_from_flags(flags.study);
  if (flags.print_spec) {
    if (plan.jobs.size() > 1) {
      spdlog::info("the study has {} runs; this is the first ({}); --controller picks another",
                   plan.jobs.size(), plan.jobs.front().controller().name());
    }
    fmt::print("{}\n", job::to_json(plan.jobs.front()));
    return std::nullopt;
  }
  for (const auto& job : plan.jobs) {
    if (job.clock() == "realtime") {
      throw std::invalid_argument(
          "--clock: realtime needs netmc-server and axis nodes (netmc run); netmc sim runs in "
          "virtual time");
    }
  }
  const unsigned threads = flags.threads > 0 ? flags.threads
                                              : std::max(1u, std::thread::hardware_concurrency());
  const FigureFormats formats = parse_figure_formats(flags.plot_format, "--plot-format");
  if (!flags.plot_dir.empty()) require_gnuplot();
  if ((!flags.csv_dir.empty() || !flags.plot_dir.empty()) && traces == TraceRecording::none) {
    traces = TraceRecording::last_iteration;
  }
  if (!flags.plot_dir.empty() && std::any_of(plan.jobs.begin(), plan.jobs.end(), job::is_spatial_job)) {
    throw std::invalid_argument("--plot: the figures are planar; a three-axis run writes its traces with --csv");
  }
  // Checked before the study runs: a bad path fails in a millisecond, not after the work.
  if (!flags.study.json_path.empty()) check_output_path(flags.study.json_path, "--json");
  if (!flags.csv_dir.empty()) check_output_directory(flags.csv_dir, "--csv");
  if (!flags.plot_dir.empty()) check_output_directory(flags.plot_dir, "--plot");
  spdlog::info("sim: {} runs on {} threads", plan.jobs.size(), threads);
  auto outcomes = run_study_in_process(plan, traces, threads);
  // Outputs are rendered completely before any file is written.
  std::string json = flags.study.json_path.empty() && flags.plot_dir.empty() && !keep_json
                         ? std::string()
                         : study_json(outcomes);
  if (!flags.study.json_path.empty()) write_output(flags.study.json_path, json);
  if (!flags.csv_dir.empty()) write_trace_directory(flags.csv_dir, outcomes);
  print_study_table(report, plan, outcomes);
  if (flags.study.curve) print_learning_curve(report, outcomes);
  if (!flags.plot_dir.empty()) {
    const std::filesystem::path dir(flags.plot_dir);
    std::filesystem::create_directories(dir);
    write_file_atomically((dir / kSimResultsFile).string(), json);
    write_trace_directory((dir / kSimTracesDir).string(), outcomes);
    const auto written = plot_sim_outputs(flags.plot_dir, flags.plot_dir, formats);
    fmt::print("\nfigures: {}\n", fmt::join(written, " "));
  }
  return SimStudy{std::move(plan), std::move(outcomes), std::move(json)};
}

std::function<int()> add_sim_command(CLI::App& app) {
  auto flags = std::make_shared<SimFlags>();
  add_sim_flags(app, *flags);
  return [flags]() -> int {
    std::ostream& report = is_standard_output(flags->study.json_path) ? std::cerr : std::cout;
    const auto study = run_sim(*flags, report, TraceRecording::none, false);
    return study ? flags->fail_on_unstable.exit_code(study->outcomes) : 0;
  };
}

}  // namespace netmc::cli
