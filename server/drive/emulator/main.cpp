// netmc-drive-emulator: one axis of a netmc plant behind a CiA 402 servo drive that speaks Modbus
// TCP, in real time. A stand-in for a fieldbus drive: run netmc-axis --drive modbus-tcp:... against
// it before the real one, and test a master's error handling with --watchdog and --fail-after.

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <iostream>
#include <limits>
#include <optional>

#include "plant/plant_catalog.hpp"
#include "server/drive/drive_spec.hpp"
#include "server/drive/emulator/drive_emulator.hpp"
#include "server/drive/modbus/duration_text.hpp"
#include "server/drive/modbus/modbus_map_file.hpp"
#include "server/log/process_log.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) { g_stop.store(true); }

struct ListenAddress {
  std::string host;
  std::uint16_t port = 0;
};

ListenAddress parse_listen(const std::string& text) {
  const auto bad = [&] {
    return std::invalid_argument("--listen: expected IPV4:PORT with PORT 0..65535 (0: any free port), got '" +
                                 text.substr(0, 64) + "'");
  };
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos) throw bad();
  const std::string port = text.substr(colon + 1);
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos ||
      std::stoi(port) > 65535) {
    throw bad();
  }
  return {text.substr(0, colon), static_cast<std::uint16_t>(std::stoi(port))};
}

double parse_max_input(const std::string& text) {
  if (text == "none") return std::numeric_limits<double>::infinity();
  double value = 0.0;
  if (!netmc::drive::parse_finite_decimal(text, value) || !(value > 0.0)) {
    throw std::invalid_argument("--max-input: expected a positive number in the plant's input unit, or none, got '" +
                                text.substr(0, 64) + "'");
  }
  return value;
}

// The plant's name and its KEY=VALUE overrides, in the syntax of --drive sim:PLANT[:KEY=VALUE,...].
netmc::drive::DriveSpec parse_plant(const std::string& text) {
  const netmc::drive::DriveSpec spec{netmc::drive::DriveSpec::Kind::simulated, text};
  try {
    spec.plant_overrides();
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    const std::string prefix = "--drive sim:";
    throw std::invalid_argument(message.rfind(prefix, 0) == 0 ? "--plant " + message.substr(prefix.size()) : message);
  }
  return spec;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"netmc-drive-emulator: a CiA 402 servo drive around one axis of a netmc plant, served over Modbus "
               "TCP in real time"};
  app.set_version_flag("--version", std::string("netmc-drive-emulator ") + NETMC_VERSION);
  std::string listen = "127.0.0.1:1502";
  std::string plant = "seed001";
  int axis = 0;
  int unit = -1;
  std::string map_file;
  std::string max_input;
  std::string cycle = "250us";
  double quick_stop = netmc::drive::EmulatedDriveSettings{}.quick_stop_deceleration_m_s2;
  std::string watchdog = "100ms";
  double initial_position = 0.0;
  std::string fail_after;
  std::string plants;
  for (const auto& name : netmc::plant::plant_names()) plants += (plants.empty() ? "" : ", ") + name;
  app.add_option("--listen", listen, "IPV4:PORT to serve on; port 0 picks a free one (logged: 'listening on ...')")
      ->capture_default_str();
  app.add_option("--plant", plant, "Plant model and its parameters: NAME[:KEY=VALUE,...], NAME one of " + plants)
      ->capture_default_str();
  app.add_option("--axis", axis, "Which axis of the plant set: 0 (X), 1 (Y), 2 (a copy of Y)")
      ->check(CLI::Range(0, 2))
      ->capture_default_str();
  app.add_option("--unit", unit, "Modbus unit id it answers (default: the map's unit_id)")->check(CLI::Range(0, 255));
  app.add_option("--map", map_file, "Register map file (default: netmc's default map, default-map.json)");
  app.add_option("--max-input", max_input,
                 "Power stage limit, the largest |plant input| (max torque), or none (default: the plant's rated "
                 "input from the catalogue)");
  app.add_option("--cycle", cycle, "Period of the drive's own loops and ticks (CSV, CSP, ramps, watchdog)")
      ->capture_default_str();
  app.add_option("--quick-stop-deceleration", quick_stop,
                 "Quick stop and fault reaction deceleration in m/s^2 until the master writes 0x6085")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--watchdog", watchdog,
                 "Fieldbus watchdog: in Operation enabled, no request for this long is a fault 0x8100 (0: off)")
      ->capture_default_str();
  app.add_option("--initial-position", initial_position, "Where the axis rests at start, metres")->capture_default_str();
  app.add_option("--fail-after", fail_after,
                 "Injected fault DURATION:KIND from DURATION after the first master connects: exception (Modbus "
                 "exception 4 to every request), wrong-unit (answers for another unit id), silence (no answers), "
                 "slow=DELAY (every answer DELAY late: 2s:slow=40ms), frozen (the actual position and velocity "
                 "registers keep their values while the drive moves on)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return e.get_exit_code() == 0 ? code : 2;
  }
  netmc::drive::emulator::DriveEmulatorSettings settings;
  netmc::drive::EmulatedDriveSettings drive_settings;
  std::unique_ptr<netmc::plant::AxisPlant> axis_plant;
  std::string plant_text, max_input_text;
  netmc::drive::modbus::ModbusMap map;
  try {
    const ListenAddress address = parse_listen(listen);
    settings.listen_host = address.host;
    settings.listen_port = address.port;
    if (unit >= 0) settings.unit = static_cast<std::uint8_t>(unit);
    settings.watchdog_s = netmc::drive::modbus::parse_duration_s(watchdog, "--watchdog");
    settings.initial_position_m = initial_position;
    if (!fail_after.empty()) settings.fault = netmc::drive::emulator::parse_injected_fault(fail_after);
    map = map_file.empty() ? netmc::drive::modbus::default_modbus_map() : netmc::drive::modbus::load_modbus_map(map_file);
    drive_settings.cycle_s = netmc::drive::modbus::parse_duration_s(cycle, "--cycle");
    if (!(drive_settings.cycle_s >= 10e-6 && drive_settings.cycle_s <= 0.1)) {
      throw std::invalid_argument("--cycle: expected 10us..100ms, got '" + cycle + "'");
    }
    drive_settings.quick_stop_deceleration_m_s2 = quick_stop;
    const netmc::drive::DriveSpec spec = parse_plant(plant);
    const std::string name = spec.plant();
    const auto index = static_cast<std::size_t>(axis);
    std::vector<netmc::plant::AxisOverrides> overrides(index + 1);
    overrides[index].parameters = spec.plant_overrides();
    auto set = netmc::plant::make_plant_set(name, index + 1, overrides);
    const std::string unit_name = netmc::plant::plant_input_unit(name);
    if (max_input.empty()) {
      drive_settings.max_input = netmc::plant::plant_rating(name).rated_input;
      max_input_text = fmt::format("{:g} {} (the plant's rated input)", drive_settings.max_input, unit_name);
    } else {
      drive_settings.max_input = parse_max_input(max_input);
      max_input_text = std::isfinite(drive_settings.max_input)
                           ? fmt::format("{:g} {}", drive_settings.max_input, unit_name)
                           : std::string("none (an ideal power stage)");
    }
    plant_text = fmt::format("{} axis {} ({})", plant, axis, set.axes[index]->describe());
    axis_plant = std::move(set.axes[index]);
  } catch (const std::invalid_argument& e) {
    std::cerr << "netmc-drive-emulator: error: " << e.what() << "\n";
    return 2;
  }
  try {
    netmc::log::init("netmc-drive-emulator");
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    const std::string origin = map.origin;
    netmc::drive::emulator::DriveEmulator emulator(std::move(axis_plant), drive_settings, std::move(map), settings);
    spdlog::info("netmc {}, plant {}, {}, unit {}, max input {}, cycle {}, quick stop {:g} m/s^2, watchdog {}, "
                 "at {:g} m, injected fault {}",
                 NETMC_VERSION, plant_text, origin, emulator.unit(), max_input_text,
                 netmc::drive::modbus::format_duration(drive_settings.cycle_s), quick_stop,
                 settings.watchdog_s > 0.0 ? netmc::drive::modbus::format_duration(settings.watchdog_s) : "off",
                 settings.initial_position_m, settings.fault ? settings.fault->describe() : "none");
    spdlog::info("listening on {}", emulator.address());
    emulator.serve(g_stop);
    return 0;
  } catch (const std::invalid_argument& e) {
    std::cerr << "netmc-drive-emulator: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "netmc-drive-emulator: error: " << e.what() << "\n";
    return 1;
  }
}
