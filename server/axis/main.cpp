// netmc-axis: one remote axis node (one or several axes) hosting a simulated plant. It applies
// the setpoints of the netmc-server that holds it and publishes feedback over DDS.

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <iostream>
#include <unistd.h>

#include "server/axis/lockstep_axis_node.hpp"
#include "server/axis/realtime_axis_node.hpp"
#include "server/dds/dds_options_cli.hpp"
#include "server/job/job_builder.hpp"
#include "server/realtime/realtime_options_cli.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) { g_stop.store(true); }

// Before it serves, a node listens this long to the others' status (three of their periods),
// so a live node with the same name or axis is seen.
constexpr std::chrono::milliseconds kClaimListen = 3 * netmc::axis::kStatusPeriod;

template <typename Node>
int serve(Node& node) {
  try {
    node.link().claim(kClaimListen);
  } catch (const netmc::axis::NodeRefused& refused) {
    std::cerr << "netmc-axis: refused: " << refused.what() << "\n";
    return 3;
  }
  std::cout << "netmc-axis " << node.link().config().node << ": serving" << std::endl;
  node.serve(g_stop);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"netmc-axis: a remote axis node hosting a simulated plant, driven over DDS"};
  netmc::axis::AxisNodeConfig config;
  std::string axes = "x,y";
  std::string clock = "lockstep";
  config.node = "axis-" + std::to_string(::getpid());
  netmc::dds::DdsOptions dds;
  app.add_option("--node", config.node, "Unique node name (default axis-PID)");
  app.add_option("--axes", axes,
                 "Axes this node hosts, comma-separated names (each unique on the DDS domain; a "
                 "job's axes default to x,y)");
  app.add_option("--plant", config.plant, "Plant model: seed001, ballscrew, linmotor, stage004");
  int watchdog_ms = 50;
  app.add_option("--clock", clock,
                 "lockstep (virtual time, deterministic) or realtime (wall clock)")
      ->check(CLI::IsMember({"lockstep", "realtime"}));
  app.add_option("--watchdog", watchdog_ms,
                 "Realtime: milliseconds without a setpoint before the axis holds (command 0)")
      ->check(CLI::Range(1, 60000));
  netmc::dds::add_time_base_option(app, config.time_base);
  netmc::dds::add_dds_options(app, dds);
  netmc::realtime::RealtimeScheduling scheduling;
  netmc::realtime::add_realtime_options(app, scheduling);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return e.get_exit_code() == 0 ? code : 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "netmc-axis: error: " << e.what() << "\n";
    return 2;
  }
  try {
    config.axes = netmc::axis::parse_axis_list(axes);
    netmc::job::check_name(config.node, "--node");
    config.clock = clock;
    dds.name = config.node;
    // Before the participant: its threads inherit the scheduling.
    const auto scheduling_outcome = netmc::realtime::apply_process_scheduling(scheduling);
    for (const auto& fallback : scheduling_outcome.fallbacks) {
      std::cerr << "netmc-axis: warning: " << fallback << "; running without it" << std::endl;
    }
    netmc::dds::DdsContext context(dds);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::cout << "netmc-axis " << config.node << ": axes " << axes << ", plant " << config.plant
              << ", clock " << clock << " (" << netmc::dds::time_base_name(config.time_base)
              << "), DDS domain " << dds.domain_id << " (" << context.describe_transport()
              << "), participant " << context.identity() << ", " << scheduling_outcome.describe() << std::endl;
    if (clock == "realtime") {
      netmc::axis::RealtimeAxisNode node(context, config, std::chrono::milliseconds(watchdog_ms));
      return serve(node);
    }
    netmc::axis::LockstepAxisNode node(context, config);
    return serve(node);
  } catch (const std::invalid_argument& e) {
    std::cerr << "netmc-axis: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "netmc-axis: error: " << e.what() << "\n";
    return 1;
  }
}
