#include "client/cli_app.hpp"

#include <CLI/CLI.hpp>

#include <iostream>
#include <stdexcept>

#include "client/cee_command.hpp"
#include "client/commissioning_commands.hpp"
#include "client/plot_command.hpp"
#include "client/qft_command.hpp"
#include "client/server_commands.hpp"
#include "client/sim_command.hpp"
#include "client/sweep_command.hpp"
#include "client/verbosity.hpp"

namespace netmc::cli {

int run_netmc(int argc, const char* const* argv) {
  verbosity() = {};
  CLI::App app{"netmc: networked motion control - studies of contouring under network delay", "netmc"};
  app.set_version_flag("--version", std::string("netmc ") + NETMC_VERSION);
  app.require_subcommand(0, 1);
  add_verbosity_flags(&app);
  app.footer(R"(Examples:
  netmc sim                                    # paper 001's study: four controllers, the table
  netmc sim --plot figures                     # ... and its figures (PNG and SVG) in figures/
  netmc sim --delay constant:4ms --controller adrc,adrc+pidccc
  netmc sweep --delay-max 0.5ms:10ms:20 --seeds 1..5 --iterations 10 --csv sweep.csv
  netmc plot --sweep sweep.csv --out figures
  netmc run --server 127.0.0.1:7300            # the same study on netmc-server + axis nodes
  netmc SUBCOMMAND --help                      # flags and examples of each subcommand

Exit codes: 0 done, 1 failed while running, 2 usage error or bad input.)");
  const auto run_sim = add_sim_command(app);
  const auto run_sweep = add_sweep_command(app);
  const auto run_plot = add_plot_command(app);
  const auto run_run = add_run_command(app);
  const auto run_submit = add_submit_command(app);
  const auto run_watch = add_watch_command(app);
  const auto run_nodes = add_nodes_command(app);
  const auto run_reset = add_reset_command(app);
  const auto run_commissioning = add_commissioning_commands(app);
  const auto run_status = add_status_command(app);
  const auto run_cancel = add_cancel_command(app);
  const auto run_jobs = add_jobs_command(app);
  const auto run_cee = add_cee_command(app);
  const auto run_qft = add_qft_command(app);
  app.get_subcommand("run")->footer(R"(Examples:
  # with netmc-server and two netmc-axis nodes running (docs/operations/distributed-runs.md)
  netmc run --server 127.0.0.1:7300                          # paper 001's study in lockstep
  netmc run --server 127.0.0.1:7300 --controller adrc+ilccc --iterations 5 --json run.json
  netmc run --server 127.0.0.1:7300 --clock realtime         # nodes started with --clock realtime

Takes every flag and preset of netmc sim; --quiet prints only the final table.)");
  app.get_subcommand("submit")->footer(R"(Examples:
  netmc submit --server 127.0.0.1:7300 --controller adrc+ilccc --iterations 50   # prints the job id
  netmc watch 7 --server 127.0.0.1:7300 --json job7.json   # from here or any other client
  netmc status --server 127.0.0.1:7300

Takes every flag and preset of netmc run except --json and --curve (a watcher writes the results).)");
  app.get_subcommand("watch")->footer(R"(Examples:
  netmc watch 7 --server 127.0.0.1:7300                   # iterations, then the table
  netmc watch 7 --server 127.0.0.1:7300 --quiet --json -  # only the result, as JSON

Exit code 1 when the job fails or is cancelled (the message says why).)");
  app.get_subcommand("nodes")->footer(R"(Examples:
  netmc nodes --server 127.0.0.1:7300     # node, axes, plant, clock, last seen, health; per axis its
                                          # drive, CiA 402 state, error code, last fault and limits)");
  app.get_subcommand("reset")->footer(R"(Examples:
  NETMC_TOKEN_FILE=admin.token netmc reset lab-x --server 10.0.0.1:7300   # every axis of node lab-x
  netmc reset lab-x --axis x                                              # one axis

Exit code 1 when the node still reports the fault (one the drive cannot clear), or is gone.)");
  app.get_subcommand("jobs")->footer(R"(Examples:
  netmc jobs --server 127.0.0.1:7300                     # the latest 50 jobs, newest first
  netmc jobs --state failed --since 24h                  # what failed since yesterday
  netmc jobs --label seed001 --limit 500 --json          # for scripts (netmc.v1.JobList))");
  app.get_subcommand("cee")->footer(R"(Examples:
  netmc cee                                # 2000 samples per contour, seed 1
  netmc cee --points 20000 --max-lag-ms 5 --normal-sd-um 10)");
  app.get_subcommand("qft")->footer(R"(Examples:
  netmc qft                                # eq. 20 against the bounds, per design frequency
  netmc qft --ccc eq20,eq19,lpccc          # paper 004's three cross-coupling controllers
  netmc qft --plot figures                 # ... plus Bode and Nichols figures (PNG, SVG))");
  for (CLI::App* subcommand : app.get_subcommands({})) add_verbosity_flags(subcommand);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11's message names the flag; one line, with where to look.
    const auto parsed = app.get_subcommands();
    const std::string help = parsed.empty() ? "netmc --help" : "netmc " + parsed.front()->get_name() + " --help";
    std::cerr << "netmc: error: " << e.what() << " (see " << help << ")\n";
    return 2;
  }
  try {
    configure_logging();
    if (app.got_subcommand("sim")) return run_sim();
    if (app.got_subcommand("sweep")) return run_sweep();
    if (app.got_subcommand("plot")) return run_plot();
    if (app.got_subcommand("run")) return run_run();
    if (app.got_subcommand("submit")) return run_submit();
    if (app.got_subcommand("watch")) return run_watch();
    if (app.got_subcommand("status")) return run_status();
    if (app.got_subcommand("cancel")) return run_cancel();
    if (app.got_subcommand("jobs")) return run_jobs();
    if (app.got_subcommand("nodes")) return run_nodes();
    if (app.got_subcommand("reset")) return run_reset();
    for (const char* name : {"enable", "disable", "quick-stop", "move", "jog"}) {
      if (app.got_subcommand(name)) return run_commissioning();
    }
    if (app.got_subcommand("cee")) return run_cee();
    if (app.got_subcommand("qft")) return run_qft();
    std::cout << app.help();
    return 0;
  } catch (const std::invalid_argument& e) {
    std::cerr << "netmc: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "netmc: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace netmc::cli
