// netmc-axis: one remote axis node (one or several axes) hosting a simulated plant. It applies
// the setpoints of netmc-server and publishes feedback over DDS.

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include "server/axis/lockstep_axis_node.hpp"
#include "server/axis/realtime_axis_node.hpp"
#include "server/dds/dds_options_cli.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) { g_stop.store(true); }

std::vector<std::uint32_t> parse_axes(const std::string& text) {
  std::vector<std::uint32_t> ids;
  std::stringstream stream(text);
  for (std::string name; std::getline(stream, name, ',');) {
    if (name == "x") {
      ids.push_back(0);
    } else if (name == "y") {
      ids.push_back(1);
    } else {
      throw std::invalid_argument("--axes: expected a comma-separated list of x, y; got '" + name + "'");
    }
  }
  if (ids.empty()) throw std::invalid_argument("--axes: expected x, y or x,y");
  return ids;
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
  app.add_option("--axes", axes, "Axes this node hosts: x, y or x,y");
  app.add_option("--plant", config.plant, "Plant model: seed001, ballscrew, linmotor, stage004");
  int watchdog_ms = 50;
  app.add_option("--clock", clock,
                 "lockstep (virtual time, deterministic) or realtime (wall clock, Asio timer)")
      ->check(CLI::IsMember({"lockstep", "realtime"}));
  app.add_option("--watchdog", watchdog_ms,
                 "Realtime: milliseconds without a setpoint before the axis holds (command 0)")
      ->check(CLI::Range(1, 60000));
  netmc::dds::add_dds_options(app, dds);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return e.get_exit_code() == 0 ? code : 2;
  }
  try {
    config.axis_ids = parse_axes(axes);
    config.clock = clock;
    dds.name = config.node;
    netmc::dds::DdsContext context(dds);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::cout << "netmc-axis " << config.node << ": axes " << axes << ", plant " << config.plant
              << ", clock " << clock << ", DDS domain " << dds.domain_id << " ("
              << context.describe_transport() << ")" << std::endl;
    if (clock == "realtime") {
      netmc::axis::RealtimeAxisNode(context, config, std::chrono::milliseconds(watchdog_ms)).serve(g_stop);
    } else {
      netmc::axis::LockstepAxisNode(context, config).serve(g_stop);
    }
    return 0;
  } catch (const std::invalid_argument& e) {
    std::cerr << "netmc-axis: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "netmc-axis: error: " << e.what() << "\n";
    return 1;
  }
}
