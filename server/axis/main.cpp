// netmc-axis: one remote axis node (one or several axes), each on a drive: netmc's simulated
// drive of a plant, a Modbus TCP drive or a lab's plugin. It applies the setpoints of the
// netmc-server that holds it, publishes feedback over DDS and enforces its own limits.

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
#include "plant/plant_catalog.hpp"
#include "server/axis/axis_drives.hpp"
#include "server/drive/drive_spec.hpp"
#include "server/job/job_builder.hpp"
#include "server/job/plant_source.hpp"
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
  CLI::App app{"netmc-axis: a remote axis node on simulated or real drives, driven over DDS"};
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
  std::string plant_flag;
  app.add_option("--plant", plant_flag,
                 "The plant model its jobs name (" + plants +
                     "): its simulated drives run it; a hardware drive is declared as it (default: the plant of "
                     "--drive sim:PLANT, else seed001)")
      ->envname("NETMC_PLANT");
  std::vector<std::string> drive_flags;
  app.add_option("--drive", drive_flags,
                 "The drive of every axis, or AXIS=DRIVE for one (repeatable): sim:PLANT[:KEY=VALUE,...] (default: "
                 "netmc's simulated drive of --plant) | modbus-tcp:HOST:PORT[,unit=N,map=FILE,timeout=DURATION] | "
                 "plugin:PATH.so[:KEY=VALUE,...]. A drive that is not simulated needs --command-limit, "
                 "--position-window and --velocity-limit (or its map file's limits)")
      ->envname("NETMC_DRIVE")
      ->take_all();
  auto* server_name_option =
      app.add_option("--server-name", config.server_name,
                     "Obey only the server whose DDS participant name is NAME (netmc-server --dds-name; under "
                     "--security its certificate must name it too); default netmc-server, the server's own default")
          ->envname("NETMC_SERVER_NAME");
  bool any_server = false;
  app.add_flag("--any-server", any_server,
               "Obey any server on the DDS domain, whatever its name (without DDS Security, any participant "
               "can then start a job on an idle axis: the axis's limits still hold)")
      ->excludes(server_name_option);
  app.add_option("--quick-stop-deceleration", config.drive_settings.quick_stop_deceleration_m_s2,
                 "Deceleration (m/s^2) of the drive's quick stop after a trip or the watchdog (CiA 402 0x6085)")
      ->check(CLI::PositiveNumber);
  auto& positioning = config.positioning;
  app.add_option("--positioning-velocity", positioning.velocity_m_s,
                 "Hardware drives: speed (m/s) of the moves to an iteration's start")
      ->check(CLI::PositiveNumber);
  app.add_option("--positioning-acceleration", positioning.acceleration_m_s2,
                 "Hardware drives: acceleration (m/s^2) of those moves and of the stop at a job's end")
      ->check(CLI::PositiveNumber);
  app.add_option("--positioning-tolerance", positioning.tolerance_m,
                 "Hardware drives: at rest within this (m) of the start before an iteration begins")
      ->check(CLI::PositiveNumber);
  int positioning_timeout_ms = 20000;
  app.add_option("--positioning-timeout", positioning_timeout_ms,
                 "Hardware drives: milliseconds beyond a move's own duration to be at rest at the start")
      ->check(CLI::Range(100, 600000));
  int watchdog_ms = 50;
  app.add_option("--clock", clock,
                 "lockstep (virtual time, deterministic) or realtime (wall clock)")
      ->check(CLI::IsMember({"lockstep", "realtime"}))
      ->envname("NETMC_CLOCK");
  app.add_option("--watchdog", watchdog_ms,
                 "Realtime: milliseconds without a setpoint before the axis quick-stops (CiA 402 Quick stop active)")
      ->check(CLI::Range(1, 60000));
  // The operator's limits (SI units): a value for every axis of the node, or AXIS=VALUE entries.
  netmc::axis::AxisLimitFlags limit_flags;
  app.add_option("--command-limit", limit_flags.command,
                 "Largest |command| the drive takes, in the plant's input unit; a larger one trips the axis "
                 "(U for every axis, or AXIS=U entries: 8,stage1.y=5; default for a simulated drive: its plant's "
                 "rated input)");
  app.add_option("--position-window", limit_flags.position_window,
                 "Travel MIN:MAX in metres; leaving it trips the axis (e.g. -0.05:0.25, or per axis: "
                 "x=-0.05:0.25,y=0:0.45; default for a simulated drive: its plant's travel)");
  app.add_option("--velocity-limit", limit_flags.velocity,
                 "Largest |velocity| in m/s; beyond it trips the axis (V, or AXIS=V entries)");
  app.add_option("--following-error-limit", limit_flags.following_error,
                 "Largest |reference - actual position| during a job's iterations; beyond it trips the axis "
                 "(LENGTH such as 2mm, or AXIS=LENGTH entries; default where the axis has a position window and a "
                 "velocity limit: a tenth of the window, at most the travel of 0.1 s at the velocity limit, at least "
                 "1 mm). The same samples trip on frozen feedback (position and velocity repeated bit for bit over 3 "
                 "samples while the reference moves faster than 20 mm/s) and on jumps (a step beyond the velocity "
                 "limit x the time between samples x 1.5); a drive on its own time must fit each cycle's exchange "
                 "in the job's period, at least 30 ms");
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
    const auto flag_limits = netmc::axis::parse_axis_limits(limit_flags, config.axes);
    netmc::job::check_name(config.node, "--node");
    if (any_server) {
      config.server_name.clear();
    } else {
      netmc::job::check_name(config.server_name, "--server-name");  // empty too: --any-server says that
    }
    config.positioning.timeout = std::chrono::milliseconds(positioning_timeout_ms);
    // The plant: --plant, else the one a simulated drive names.
    std::string plant = plant_flag;
    for (const auto& value : drive_flags) {
      const std::size_t equals = value.find('=');
      const std::string spec = equals != std::string::npos && value.substr(0, equals).find(':') == std::string::npos
                                   ? value.substr(equals + 1)
                                   : value;
      if (plant.empty() && spec.rfind("sim:", 0) == 0) plant = netmc::drive::parse_drive_spec(spec).plant();
    }
    if (plant.empty()) plant = "seed001";
    // A known plant, or the catalog's message; a plant from a file is opened and checked now.
    if (netmc::plant::is_file_plant(plant)) {
      // As a contour job builds it (two axes, three for a three-axis node).
      netmc::job::make_job_plant_set(plant, config.axes.size() == 3 ? 3 : 2);
    } else {
      netmc::plant::plant_rating(plant);
    }
    const auto drive_specs = netmc::drive::parse_drive_flags(drive_flags, config.axes, plant);
    config.plant = netmc::axis::node_plant(drive_specs, plant);
    bool hardware = false;
    for (const auto& [axis, spec] : drive_specs) hardware = hardware || spec.kind != netmc::drive::DriveSpec::Kind::simulated;
    if (hardware && clock != "realtime") {
      throw std::invalid_argument("--drive: a drive that is not simulated runs on its own time: start the node with "
                                  "--clock realtime (lockstep is virtual time, for simulated drives)");
    }
    netmc::log::init("netmc-axis " + config.node);
    config.clock = clock;
    dds.name = config.node;
    // Before the participant: its threads inherit the scheduling.
    const auto scheduling_outcome = netmc::realtime::apply_process_scheduling(scheduling);
    for (const auto& fallback : scheduling_outcome.fallbacks) {
      spdlog::warn("{}; running without it", fallback);
    }
    // Hardware is opened before the node joins the domain: one that cannot be reached, or whose
    // limits are missing, refuses the start.
    config.drives = netmc::axis::open_axis_drives(drive_specs, flag_limits, config.drive_settings);
    std::map<std::string, netmc::drive::AxisLimits> limits;
    std::string drives_text;
    for (const auto& axis : config.axes) {
      limits[axis] = config.drives.at(axis).limits;
      const auto& entry = config.drives.at(axis);
      drives_text += (drives_text.empty() ? "" : ", ") + axis + " " +
                     (entry.hardware ? entry.hardware->describe() : entry.spec.describe());
    }
    netmc::dds::DdsContext context(dds);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::signal(SIGUSR1, on_reset);
    spdlog::info("netmc {}, axes {}, plant {}, drives {}, limits {}, clock {} ({}), DDS domain {} ({}), "
                 "participant {}, {}{}",
                 NETMC_VERSION, axes, config.plant, drives_text, netmc::axis::describe_axis_limits(limits, config.axes), clock,
                 netmc::dds::time_base_name(config.time_base), dds.domain_id, context.describe_transport(),
                 context.identity(), scheduling_outcome.describe(),
                 config.server_name.empty() ? ", obeys any server (--any-server)"
                                             : ", obeys server " + config.server_name + " only");
    if (clock == "realtime") {
      netmc::axis::RealtimeAxisNode node(context, config, std::chrono::milliseconds(watchdog_ms));
      return serve(node);
    }
    netmc::axis::LockstepAxisNode node(context, config);
    return serve(node);
  } catch (const std::invalid_argument& e) {
    std::cerr << "netmc-axis: error: " << e.what() << "\n";
    return 2;
  } catch (const netmc::drive::DriveError& e) {
    std::cerr << "netmc-axis: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "netmc-axis: error: " << e.what() << "\n";
    return 1;
  }
}
