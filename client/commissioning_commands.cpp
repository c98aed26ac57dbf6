#include "client/commissioning_commands.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include "client/server_commands.hpp"
#include "idl/management.pb.h"
#include "server/job/quantity_text.hpp"

namespace netmc::cli {
namespace {

using Clock = std::chrono::steady_clock;
using Kind = netmc::v1::AxisCommand;

struct Flags {
  std::string server = "127.0.0.1:7300";
  std::string node;
  std::string axis;
  std::string to;          // move: the target position
  std::string speed;       // move: cruise speed; jog: signed speed
  std::string duration = "1s";  // jog
  std::string tolerance = "1um";  // move: at rest within this of the target
  int wait_ms = 5000;
};

// The node's view of one axis, as the server last heard it (nullopt: node or axis not listed).
std::optional<netmc::v1::AxisDriveInfo> axis_view(const std::string& server, const std::string& node,
                                                  const std::string& axis) {
  const auto reply = ask_server(server, [](netmc::v1::Request& request) { request.mutable_nodes(); }).nodes();
  for (const auto& listed : reply.nodes()) {
    if (listed.node() != node) continue;
    for (const auto& drive : listed.drives()) {
      if (drive.axis() == axis) return drive;
    }
  }
  return std::nullopt;
}

std::string describe(const netmc::v1::AxisDriveInfo& drive) {
  return fmt::format("axis {}: {}, {} at {:.6f} m, {:+.6f} m/s, following error {:+.3f} um", drive.axis(),
                     drive.motion(), drive.state(), drive.position_m(), drive.velocity_m_s(),
                     drive.following_error_m() * 1e6);
}

// Sends one command; returns its number and the axes it went to.
std::pair<std::uint64_t, std::vector<std::string>> send(const Flags& flags, Kind::Kind kind, double target_m,
                                                        double speed_m_s) {
  const auto response = ask_server(flags.server, [&](netmc::v1::Request& request) {
    auto& command = *request.mutable_axis_command();
    command.set_node(flags.node);
    command.set_axis(flags.axis);
    command.set_kind(kind);
    command.set_target_m(target_m);
    command.set_speed_m_s(speed_m_s);
  });
  std::vector<std::string> axes;
  if (!flags.axis.empty()) {
    axes.push_back(flags.axis);
  } else {
    for (const auto& axis : response.axis_command().node().axes()) axes.push_back(axis);
  }
  return {response.axis_command().command_number(), axes};
}

// Waits until the node has taken command `number` on `axis` and `done` holds; throws with the
// node's reason for a refusal, for a motion that ended otherwise (`ended_is_failure`: a trip, a
// drive that left Operation enabled), or when `wait` passes first.
netmc::v1::AxisDriveInfo wait_for(const Flags& flags, const std::string& axis, std::uint64_t number,
                                  std::chrono::milliseconds wait,
                                  const std::function<bool(const netmc::v1::AxisDriveInfo&)>& done,
                                  const std::string& waiting_for, bool ended_is_failure = true) {
  const auto deadline = Clock::now() + wait;
  const std::string where = "node " + flags.node + ", axis " + axis + ": ";
  while (true) {
    const auto view = axis_view(flags.server, flags.node, axis);
    if (!view) throw std::runtime_error("node " + flags.node + " is no longer listed by the server");
    const bool taken = view->command_number() == number;
    if (taken) {
      if (view->command_refused()) throw std::runtime_error(where + "refused: " + view->command_note());
      if (done(*view)) return *view;
      if (ended_is_failure && view->motion() == "off" && !view->command_note().empty()) {
        throw std::runtime_error(where + view->command_note());
      }
    }
    if (Clock::now() >= deadline) {
      throw std::runtime_error(fmt::format("{}{} after {} ms ({}{})", where,
                                           taken ? "not " + waiting_for : "the node did not take the command",
                                           wait.count(), describe(*view),
                                           view->command_note().empty() ? "" : "; " + view->command_note()));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

std::atomic<bool>& interrupted() {
  static std::atomic<bool> flag{false};
  return flag;
}
extern "C" void on_interrupt(int) { interrupted().store(true); }

CLI::App* add_axis_command(CLI::App& app, const char* name, const std::string& help, Flags& flags, bool axis_required) {
  CLI::App* command =
      app.add_subcommand(name, help + " Needs the server's admin token where it has one (NETMC_TOKEN_FILE).");
  command->add_option("NODE", flags.node, "The node's name (netmc nodes lists them)")->required();
  auto* axis = command->add_option("AXIS", flags.axis, axis_required ? "The axis" : "One axis (default: every axis "
                                                                                    "of the node)");
  if (axis_required) axis->required();
  add_server_option(command, flags.server);
  return command;
}

int power_command(const Flags& flags, Kind::Kind kind) {
  const auto [number, axes] = send(flags, kind, 0.0, 0.0);
  const std::string goal = kind == Kind::ENABLE ? "holding" : "off";
  for (const auto& axis : axes) {
    const auto view = wait_for(
        flags, axis, number, std::chrono::milliseconds(flags.wait_ms),
        [&](const netmc::v1::AxisDriveInfo& drive) {
          if (kind == Kind::QUICK_STOP) return drive.state() != "Operation enabled" && drive.state() != "Quick stop active";
          return drive.motion() == goal;
        },
        kind == Kind::ENABLE ? "holding in Operation enabled" : kind == Kind::DISABLE ? "switched off" : "stopped",
        kind == Kind::ENABLE);
    fmt::print("{}\n", describe(view));
  }
  return 0;
}

int move_command(const Flags& flags) {
  const double target = job::parse_quantity(flags.to, job::Quantity::length, "--to");
  const double speed = flags.speed.empty() ? 0.0 : job::parse_quantity(flags.speed, job::Quantity::speed, "--speed");
  const double tolerance = job::parse_quantity(flags.tolerance, job::Quantity::length, "--tolerance");
  if (!(speed >= 0.0)) throw std::invalid_argument("--speed: expected a positive speed such as 10mm/s");
  if (!(tolerance > 0.0)) throw std::invalid_argument("--tolerance: expected a positive length such as 1um");
  const auto started = Clock::now();
  const auto [number, axes] = send(flags, Kind::MOVE, target, speed);
  const auto view = wait_for(
      flags, flags.axis, number, std::chrono::milliseconds(flags.wait_ms),
      [&](const netmc::v1::AxisDriveInfo& drive) {
        return drive.motion() == "holding" && std::abs(drive.position_m() - target) <= tolerance;
      },
      fmt::format("at rest within {:g} um of {:.6f} m", tolerance * 1e6, target));
  fmt::print("{} (target {:.6f} m, off by {:+.3f} um; {:.2f} s)\n", describe(view), target,
             (view.position_m() - target) * 1e6, std::chrono::duration<double>(Clock::now() - started).count());
  return 0;
}

int jog_command(const Flags& flags) {
  const double speed = job::parse_quantity(flags.speed, job::Quantity::speed, "--speed");
  const double duration = job::parse_quantity(flags.duration, job::Quantity::time, "--for");
  if (!(speed != 0.0 && std::isfinite(speed))) throw std::invalid_argument("--speed: expected a non-zero speed such as -5mm/s");
  if (!(duration > 0.0 && duration <= 60.0)) throw std::invalid_argument("--for: expected a duration in (0, 60] s");
  // The node stops a jog whose commands stop coming (its deadman): renewed every 100 ms, and
  // stopped at once on Ctrl-C.
  interrupted().store(false);
  const auto previous = std::signal(SIGINT, on_interrupt);
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(duration));
  std::uint64_t number = 0;
  try {
    number = send(flags, Kind::JOG, 0.0, speed).first;
    wait_for(flags, flags.axis, number, std::chrono::milliseconds(flags.wait_ms),
             [](const netmc::v1::AxisDriveInfo& drive) { return drive.motion() == "jogging" || drive.motion() == "holding"; },
             "jogging");
    while (Clock::now() < end && !interrupted().load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      send(flags, Kind::JOG, 0.0, speed);
    }
    number = send(flags, Kind::JOG, 0.0, 0.0).first;
  } catch (...) {
    std::signal(SIGINT, previous);
    throw;
  }
  std::signal(SIGINT, previous);
  const auto view = wait_for(flags, flags.axis, number, std::chrono::milliseconds(flags.wait_ms),
                             [](const netmc::v1::AxisDriveInfo& drive) { return drive.motion() == "holding"; },
                             "at rest after the jog");
  fmt::print("{}{}\n", describe(view), view.command_note().empty() ? "" : " (" + view.command_note() + ")");
  return 0;
}

}  // namespace

std::function<int()> add_commissioning_commands(CLI::App& app) {
  auto enable = std::make_shared<Flags>();
  auto disable = std::make_shared<Flags>();
  auto quick_stop = std::make_shared<Flags>();
  auto move = std::make_shared<Flags>();
  auto jog = std::make_shared<Flags>();
  CLI::App* enable_app = add_axis_command(app, "enable",
                                          "Enable a node's hardware axes that no job holds (CiA 402 to Operation "
                                          "enabled, CSP holding where each stands); waits until they hold.",
                                          *enable, false);
  CLI::App* disable_app = add_axis_command(
      app, "disable", "Bring enabled axes to rest on the positioning deceleration, then switch their power stage off.",
      *disable, false);
  CLI::App* quick_stop_app = add_axis_command(
      app, "quick-stop",
      "The drives' own quick stop, at once; a job holding an axis fails. Waits until the axes have stopped.",
      *quick_stop, false);
  CLI::App* move_app = add_axis_command(
      app, "move",
      "Move an enabled axis to a position and wait until it stands there: a time-optimal profile under the node's "
      "positioning acceleration, inside the axis's window and velocity limit, supervised (a following error beyond "
      "2 mm quick-stops it).",
      *move, true);
  move_app->add_option("--to", move->to, "Target position: 10mm, 0.055 (m)")->required();
  move_app->add_option("--speed", move->speed, "Cruise speed: 20mm/s (default: the node's --positioning-velocity)");
  move_app->add_option("--tolerance", move->tolerance, "At rest within this of the target: 1um (the default)");
  move->wait_ms = 60000;
  CLI::App* jog_app = add_axis_command(
      app, "jog",
      "Jog an enabled axis at a speed (its sign the direction) for --for, or until Ctrl-C, stopping at its window's "
      "edge; the node stops it 0.5 s after its commands stop coming.",
      *jog, true);
  jog_app->add_option("--speed", jog->speed, "Jog speed, signed: 5mm/s, -2mm/s")->required();
  jog_app->add_option("--for", jog->duration, "How long: 1s (the default), at most 60s");
  for (auto [command, flags] : {std::pair{enable_app, enable}, std::pair{disable_app, disable},
                                std::pair{quick_stop_app, quick_stop}, std::pair{move_app, move}, std::pair{jog_app, jog}}) {
    command->add_option("--wait", flags->wait_ms, "Milliseconds to wait for the node to report the command done")
        ->check(CLI::Range(0, 600000));
  }
  app.get_subcommand("move")->footer(R"(Examples:
  netmc enable rig x --server 127.0.0.1:7300
  netmc move rig x --to 65mm --speed 10mm/s
  netmc jog rig x --speed -5mm/s --for 2s
  netmc disable rig x)");
  return [enable_app, disable_app, quick_stop_app, move_app, jog_app, enable, disable, quick_stop, move, jog]() -> int {
    if (enable_app->parsed()) return power_command(*enable, Kind::ENABLE);
    if (disable_app->parsed()) return power_command(*disable, Kind::DISABLE);
    if (quick_stop_app->parsed()) return power_command(*quick_stop, Kind::QUICK_STOP);
    if (move_app->parsed()) return move_command(*move);
    if (jog_app->parsed()) return jog_command(*jog);
    return 0;
  };
}

}  // namespace netmc::cli
