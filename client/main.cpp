// netmc: the client CLI. `netmc sim` runs studies in-process; with no arguments it runs the
// paper-001 study and prints the comparison table.

#include <CLI/CLI.hpp>

#include <iostream>
#include <stdexcept>

#include "client/cee_command.hpp"
#include "client/server_commands.hpp"
#include "client/sim_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"netmc: networked motion control - studies of contouring under network delay"};
  app.require_subcommand(0, 1);
  const auto run_sim = netmc::cli::add_sim_command(app);
  const auto run_run = netmc::cli::add_run_command(app);
  const auto run_nodes = netmc::cli::add_nodes_command(app);
  const auto run_cee = netmc::cli::add_cee_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  try {
    if (app.got_subcommand("sim")) return run_sim();
    if (app.got_subcommand("run")) return run_run();
    if (app.got_subcommand("nodes")) return run_nodes();
    if (app.got_subcommand("cee")) return run_cee();
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
