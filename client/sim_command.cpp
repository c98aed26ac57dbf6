#include "client/sim_command.hpp"

#include <iostream>
#include <thread>

#include "client/study_flags.hpp"
#include "client/study_report.hpp"
#include "client/study_runner.hpp"

namespace netmc::cli {

std::function<int()> add_sim_command(CLI::App& app) {
  struct Flags {
    StudyFlags study;
    std::string csv_dir;
    unsigned threads = 0;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* sim = app.add_subcommand("sim", "Run a study in-process, in virtual time (default: --preset seed001)");
  add_study_flags(sim, flags->study);
  sim->add_option("--csv", flags->csv_dir, "Write per-cycle traces of each run's last iteration into DIR");
  sim->add_option("--threads", flags->threads, "Worker threads (default: all cores)");

  return [flags]() -> int {
    const StudyPlan plan = plan_from_flags(flags->study);
    for (const auto& job : plan.jobs) {
      if (job.clock() == "realtime") {
        throw std::invalid_argument(
            "--clock: realtime needs netmc-server and axis nodes (netmc run); netmc sim runs in "
            "virtual time");
      }
    }
    const unsigned threads = flags->threads > 0 ? flags->threads
                                                : std::max(1u, std::thread::hardware_concurrency());
    const auto outcomes = run_study_in_process(plan, !flags->csv_dir.empty(), threads);
    // Outputs are rendered completely before any file is written.
    const std::string json = flags->study.json_path.empty() ? std::string() : study_json(outcomes);
    if (!flags->study.json_path.empty()) write_file_atomically(flags->study.json_path, json);
    if (!flags->csv_dir.empty()) write_trace_directory(flags->csv_dir, outcomes);
    print_study_table(std::cout, plan, outcomes);
    if (flags->study.curve) print_learning_curve(std::cout, outcomes);
    return 0;
  };
}

}  // namespace netmc::cli
