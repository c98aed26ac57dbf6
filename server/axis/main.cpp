// netmc-axis: one remote axis node (one or several axes) hosting a simulated plant. It applies
// the setpoints of the netmc-server that holds it and publishes feedback over DDS.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <iostream>
#include <unistd.h>

#include "server/axis/axis_limit_flags.hpp"
#include "server/axis/lockstep_axis_node.hpp"
#include "server/axis/realtime_axis_node.hpp"
#include "server/dds/dds_options_cli.hpp"
#include "server/job/job_builder.hpp"
#include "plant/plant_catalog.hpp"
#include "server/log/process_log.hpp"
#include "server/realtime/realtime_options_cli.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) { g_stop.store(true); }
void on_reset(int) { netmc::axis::fault_reset_requested().store(true); }

// Before it serves, a node listens this long to the others' status (three of their periods),
// so a live node with the same name or axis is seen.
constexpr std::chrono::milliseconds kClaimListen = 3 * netmc::axis::kStatusPeriod;

template <typename Node>
int serve(Node& node) {
  try {
    node.link().claim(kClaimListen);
  } catch (const netmc::axis::NodeRefused& refused) {
    spdlog::error("refused: {}", refused.what());
    return 3;
  }
  spdlog::info("serving");
  node.serve(g_stop);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"netmc-axis: a remote axis node hosting a simulated plant, driven over DDS"};
  app.set_version_flag("--version", std::string("netmc-axis ") + NETMC_VERSION);
  netmc::axis::AxisNodeConfig config;
  std::string axes = "x,y";
  std::string clock = "lockstep";
  config.node = "axis-" + std::to_string(::getpid());
  netmc::dds::DdsOptions dds;
  app.add_option("--node", config.node, "Unique node name (default axis-PID)")->envname("NETMC_NODE");
  app.add_option("--axes", axes,
                 "Axes this node hosts, comma-separated names (each unique on the DDS domain; a "
                 "job's axes default to x,y)")
      ->envname("NETMC_AXES");
  std::string plants;
  for (const auto& name : netmc::plant::plant_names()) plants += (plants.empty() ? "" : ", ") + name;
  app.add_option("--plant", config.plant, "Plant model: " + plants)->envname("NETMC_PLANT");
  int watchdog_ms = 50;
  app.add_option("--clock", clock,
                 "lockstep (virtual time, deterministic) or realtime (wall clock)")
      ->check(CLI::IsMember({"lockstep", "realtime"}))
      ->envname("NETMC_CLOCK");
  app.add_option("--watchdog", watchdog_ms,
                 "Realtime: milliseconds without a setpoint before the axis holds (command 0)")
      ->check(CLI::Range(1, 60000));
  // The operator's limits (SI units): a value for every axis of the node, or AXIS=VALUE entries.
  netmc::axis::AxisLimitFlags limit_flags;
  app.add_option("--command-limit", limit_flags.command,
                 "Largest |command| the drive takes, in the plant's input unit; a larger one trips the axis "
                 "(U for every axis, or AXIS=U entries: 8,stage1.y=5)");
  app.add_option("--position-window", limit_flags.position_window,
                 "Travel MIN:MAX in metres; leaving it trips the axis (e.g. -0.05:0.25, or per axis: "
                 "x=-0.05:0.25,y=0:0.45)");
  app.add_option("--velocity-limit", limit_flags.velocity,
                 "Largest |velocity| in m/s; beyond it trips the axis (V, or AXIS=V entries)");
  app.add_option("--slew-limit", limit_flags.slew,
                 "Largest change of the applied command per second (units/s): steps are ramped, not tripped "
                 "(R, or AXIS=R entries)");
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
    config.limits = netmc::axis::parse_axis_limits(limit_flags, config.axes);
    netmc::job::check_name(config.node, "--node");
    netmc::log::init("netmc-axis " + config.node);
    config.clock = clock;
    dds.name = config.node;
    // Before the participant: its threads inherit the scheduling.
    const auto scheduling_outcome = netmc::realtime::apply_process_scheduling(scheduling);
    for (const auto& fallback : scheduling_outcome.fallbacks) {
      spdlog::warn("{}; running without it", fallback);
    }
    netmc::dds::DdsContext context(dds);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::signal(SIGUSR1, on_reset);
    spdlog::info("netmc {}, axes {}, plant {}, limits {}, clock {} ({}), DDS domain {} ({}), participant {}, {}",
                 NETMC_VERSION, axes, config.plant, netmc::axis::describe_axis_limits(config.limits, config.axes), clock,
                 netmc::dds::time_base_name(config.time_base), dds.domain_id, context.describe_transport(),
                 context.identity(), scheduling_outcome.describe());
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
