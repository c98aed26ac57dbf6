#include "client/sweep_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>

#include "client/figures.hpp"
#include "client/progress_bar.hpp"
#include "client/server_commands.hpp"
#include "client/study_report.hpp"
#include "client/study_runner.hpp"
#include "client/sweep_grid.hpp"
#include "client/sweep_output.hpp"
#include "client/sweep_shard.hpp"
#include "client/verbosity.hpp"

namespace netmc::cli {

SweepCommand add_sweep_flags(CLI::App& app, SweepFlags& flags) {
  CLI::App* sweep = app.add_subcommand(
      "sweep", "Run a grid of studies (preset/trajectory x controller x delay x seed) on all cores");
  sweep->add_option("--preset", flags.presets, "Base studies, comma-separated (default seed001)")
      ->type_name("NAME[,...]");
  sweep->add_option("--trajectory", flags.axes.trajectories,
                    "Trajectory axis: give the flag once per value (forms as in sim)")
      ->type_name("SHAPE:...");
  sweep->add_option("--controller", flags.axes.controllers,
                    "Controller axis, comma-separated (default: the runs of each preset)")
      ->type_name("NAME[,...]");
  sweep->add_option("--delay-max", flags.axes.delay_max,
                    "Delay axis: upper bounds of a uniform loop delay, START:STOP:COUNT or a list "
                    "(0.5ms:10ms:20, 1ms,2ms,5ms)")
      ->type_name("RANGE|LIST");
  sweep->add_option("--delay-min", flags.axes.delay_min,
                    "Lower bound of the uniform delay with --delay-max (default 0.3ms, paper 001)")
      ->type_name("DURATION");
  sweep->add_option("--delay", flags.axes.delays,
                    "Delay axis as whole delay specs: give the flag once per value (forms as in sim)")
      ->type_name("KIND:...");
  sweep->add_option("--seeds", flags.axes.seeds, "Seed axis: FIRST..LAST or a list (default: the preset's seed)")
      ->type_name("FIRST..LAST|LIST");
  sweep->add_option("--spec", flags.axes.fixed.spec_file, "Base job spec as JSON instead of a preset")
      ->type_name("FILE.json");
  add_job_override_flags(sweep, flags.axes.fixed);
  sweep->add_option("--threads", flags.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  sweep->add_option("--csv", flags.csv_path, "Write the tidy CSV: one row per configuration and iteration")
      ->type_name("FILE");
  sweep->add_option("--json", flags.json_path, "Write every configuration and its iterations as JSON")
      ->type_name("FILE");
  sweep->add_option("--plot", flags.plot_dir,
                    "Draw e_max and e_sum vs the delay bound into DIR (as netmc plot --sweep)")
      ->type_name("DIR");
  sweep->add_option("--server", flags.server,
                    "Run the configurations one after another on this netmc-server (HOST:PORT) "
                    "instead of in-process")
      ->type_name("HOST:PORT");
  sweep->add_option("--shard", flags.shard,
                    "Run only the K-th of N interleaved parts of the grid (configurations K, K+N, ...) and "
                    "write part files for netmc sweep merge: one per machine or job-array task")
      ->type_name("K/N");
  CLI::App* merge = sweep->add_subcommand(
      "merge", "Join the part files of netmc sweep --shard K/N (all CSV or all JSON) into what the unsharded "
               "sweep writes");
  merge->add_option("parts", flags.merge_parts, "The part files, one per K of 1..N, in any order")
      ->required()
      ->type_name("PART...");
  merge->add_option("-o,--output", flags.merge_output, "Where the joined file goes (default '-': standard output)")
      ->type_name("FILE");
  sweep->footer(R"(Examples:
  # Paper 001's four controllers x 20 delay bounds (0.5..10 ms) x 5 seeds = 400 configurations
  netmc sweep --delay-max 0.5ms:10ms:20 --seeds 1..5 --iterations 10 --csv sweep.csv --json sweep.json
  # Two controllers, three constant delays, with the figures
  netmc sweep --controller adrc,adrc+ilccc --delay constant:1ms --delay constant:5ms \
      --delay constant:10ms --csv sweep.csv --plot figures
  # Two base studies with their own trajectories
  netmc sweep --preset seed001,seed001-ellipse --seeds 1..3 --csv sweep.csv
  # The same grid in three parts (three machines, or a Slurm array), then joined
  netmc sweep --delay-max 1ms:8ms:4 --seeds 1..3 --shard 2/3 --csv part-2.csv   # ... and 1/3, 3/3
  netmc sweep merge part-1.csv part-2.csv part-3.csv -o sweep.csv

Configurations run in grid order (preset, trajectory, run, delay, seed; the last varies
fastest) and results are the same for any --threads. Files are written whole, and only after
every configuration has finished. A run that becomes unstable stops at that iteration.)");

  return {sweep, merge};
}

std::string run_sweep_merge(const SweepFlags& flags) {
  if (!is_standard_output(flags.merge_output)) check_output_path(flags.merge_output, "--output");
  std::vector<std::pair<std::string, std::string>> parts;
  for (const auto& path : flags.merge_parts) parts.emplace_back(path, read_sweep_part(path));
  std::string merged = merge_sweep_parts(parts);
  write_output(flags.merge_output, merged);
  if (!is_standard_output(flags.merge_output)) fmt::print("merged {} parts into {}\n", parts.size(), flags.merge_output);
  return merged;
}

std::vector<SweepConfiguration> expand_sweep_flags(const SweepFlags& flags) {
  SweepAxes axes = flags.axes;
  axes.presets = split_list(flags.presets);
  if (!flags.presets.empty() && axes.presets.empty()) {
    throw std::invalid_argument("--preset: expected NAME[,NAME...]");
  }
  return expand_sweep(axes);
}

SweepStudy run_sweep(const SweepFlags& flags, const SweepRunOptions& options) {
  if (!flags.csv_path.empty()) check_output_path(flags.csv_path, "--csv");
  if (!flags.json_path.empty()) check_output_path(flags.json_path, "--json");
  if (is_standard_output(flags.csv_path) && is_standard_output(flags.json_path)) {
    throw std::invalid_argument("--csv, --json: only one of them can be '-' (standard output)");
  }
  if (!flags.plot_dir.empty()) require_gnuplot();
  const auto whole_grid = expand_sweep_flags(flags);
  std::optional<SweepShard> shard;
  if (!flags.shard.empty()) {
    shard = parse_sweep_shard(flags.shard, "--shard");
    if (!flags.plot_dir.empty()) {
      throw std::invalid_argument("--plot: a part has a part of the grid; draw the merged file with netmc plot --sweep");
    }
    if (flags.csv_path.empty() && flags.json_path.empty() && !options.keep_csv && !options.keep_json) {
      throw std::invalid_argument("--shard: a part is for netmc sweep merge; give --csv FILE or --json FILE");
    }
  }
  std::vector<SweepConfiguration> grid;
  for (const auto& configuration : whole_grid) {
    if (!shard || shard->contains(configuration.number)) grid.push_back(configuration);
  }
  StudyPlan plan;
  std::size_t total_iterations = 0;
  for (const auto& configuration : grid) {
    if (configuration.job.clock() == "realtime" && flags.server.empty()) {
      throw std::invalid_argument("--clock: realtime needs --server");
    }
    plan.jobs.push_back(configuration.job);
    total_iterations += configuration.job.iterations();
  }
  const unsigned threads = flags.threads > 0 ? flags.threads
                                              : std::max(1u, std::thread::hardware_concurrency());
  spdlog::info("sweep: {} configurations, {} iterations in all, {}", grid.size(), total_iterations,
               flags.server.empty() ? fmt::format("{} threads in-process", threads)
                                     : "on server " + flags.server);

  ProgressBar progress(total_iterations, "iterations",
                       options.progress ? ProgressBar::style_for_stderr(verbosity().quiet) : ProgressBar::Style::off,
                       std::cerr);
  const auto start = std::chrono::steady_clock::now();
  std::vector<RunOutcome> outcomes;
  if (flags.server.empty()) {
    outcomes = run_study_in_process(plan, TraceRecording::none, threads, [&] { progress.advance(); });
  } else {
    management::ManagementClient client(flags.server, kServerConnectTimeout);
    std::uint64_t request_id = 1;
    for (const auto& job : plan.jobs) {
      outcomes.push_back(run_job_on_server(client, job, request_id++, flags.server, true,
                                           [&] { progress.advance(); }));
    }
  }
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Render everything before writing anything.
  const bool need_csv = !flags.csv_path.empty() || !flags.plot_dir.empty() || options.keep_csv;
  std::string csv = need_csv ? sweep_csv(grid, outcomes) : std::string();
  std::string json = flags.json_path.empty() && !options.keep_json ? std::string() : sweep_json(grid, outcomes);
  if (shard) {
    const std::string fingerprint = sweep_grid_fingerprint(whole_grid);
    if (!csv.empty()) csv = sweep_csv_part(*shard, fingerprint, whole_grid.size(), csv);
    if (!json.empty()) json = sweep_json_part(*shard, fingerprint, whole_grid.size(), json);
  }
  if (!flags.csv_path.empty()) write_output(flags.csv_path, csv);
  if (!flags.json_path.empty()) write_output(flags.json_path, json);

  // With an output on standard output, the report goes to standard error.
  const bool piped = is_standard_output(flags.csv_path) || is_standard_output(flags.json_path);
  std::ostream& report = options.report ? *options.report : piped ? std::cerr : std::cout;
  print_sweep_summary(report, grid, outcomes);
  std::size_t iterations_run = 0;
  for (const auto& outcome : outcomes) iterations_run += static_cast<std::size_t>(outcome.result.iterations_size());
  fmt::print(report, "\n{} configurations{}, {} iterations run, in {:.2f} s ({})\n", grid.size(),
             shard ? fmt::format(" (part {}/{} of {})", shard->index, shard->count, whole_grid.size()) : "",
             iterations_run, seconds, flags.server.empty() ? fmt::format("{} threads", threads) : "server " + flags.server);
  for (const auto* path : {&flags.csv_path, &flags.json_path}) {
    if (!path->empty() && !is_standard_output(*path)) fmt::print(report, "wrote {}\n", *path);
  }
  if (!flags.plot_dir.empty()) {
    const std::string data_dir = (std::filesystem::path(flags.plot_dir) / "data").string();
    std::filesystem::create_directories(data_dir);
    const auto figures = sweep_figures(CsvTable::parse(csv, "sweep"), {"e_max_m", "e_sum_m"}, data_dir);
    for (const auto& file : render_figures(figures, flags.plot_dir, {}, "sweep")) fmt::print(report, "wrote {}\n", file);
  }
  return SweepStudy{std::move(csv), std::move(json), grid.size(), whole_grid.size()};
}

std::function<int()> add_sweep_command(CLI::App& app) {
  auto flags = std::make_shared<SweepFlags>();
  const SweepCommand command = add_sweep_flags(app, *flags);
  return [flags, merge = command.merge]() -> int {
    if (merge->parsed()) {
      run_sweep_merge(*flags);
      return 0;
    }
    run_sweep(*flags, {});
    return 0;
  };
}

}  // namespace netmc::cli
