#include "server/axis/axis_drives.hpp"

#include <cmath>
#include <stdexcept>

#include "plant/plant_catalog.hpp"
#include "server/drive/modbus/modbus_tcp_drive.hpp"
#include "server/drive/plugin/plugin_drive.hpp"
#include "server/sim/axis_endpoint.hpp"

namespace netmc::axis {
namespace {

std::unique_ptr<drive::Drive> open_hardware(const drive::DriveSpec& spec) {
  std::unique_ptr<drive::Drive> hardware;
  if (spec.kind == drive::DriveSpec::Kind::modbus_tcp) hardware = drive::modbus::ModbusTcpDrive::from_spec(spec.text);
  if (spec.kind == drive::DriveSpec::Kind::plugin) hardware = drive::PluginDrive::load(spec.text);
  if (!hardware) throw std::invalid_argument("--drive " + spec.describe() + ": not a hardware drive");
  hardware->open();
  return hardware;
}

drive::AxisLimits rating_limits(const std::string& plant) {
  const plant::PlantRating rating = plant::plant_rating(plant);
  drive::AxisLimits limits;
  limits.command = rating.rated_input;
  limits.position_min_m = rating.travel_min_m;
  limits.position_max_m = rating.travel_max_m;
  return limits;
}

// Hardware, and models netmc has no rating of, run only inside limits the operator gave.
void require_limits(const drive::AxisLimits& limits, const std::string& axis, const drive::DriveSpec& spec,
                    const std::string& what) {
  std::string missing;
  if (std::isinf(limits.command)) missing += " a command limit (--command-limit),";
  if (std::isinf(limits.position_min_m) || std::isinf(limits.position_max_m)) {
    missing += " a position window (--position-window),";
  }
  if (std::isinf(limits.velocity_m_s)) missing += " a velocity limit (--velocity-limit),";
  if (!missing.empty()) {
    missing.pop_back();
    throw std::invalid_argument("axis " + axis + " (" + spec.describe().substr(0, 200) + "): " + what + " needs" +
                                missing + " from the flags" +
                                (spec.kind == drive::DriveSpec::Kind::simulated ? "" : " or its map file") +
                                "; refusing to start without them");
  }
}

}  // namespace

std::string node_plant(const std::map<std::string, drive::DriveSpec>& specs, const std::string& plant_flag) {
  std::string plant = plant_flag;
  for (const auto& [axis, spec] : specs) {
    if (spec.kind != drive::DriveSpec::Kind::simulated) continue;
    if (plant.empty()) plant = spec.plant();
    if (spec.plant() != plant) {
      throw std::invalid_argument("--drive " + axis + "=" + spec.describe() + ": the node's plant is '" + plant +
                                  "': a node's simulated drives and the model its jobs name are one plant");
    }
  }
  return plant.empty() ? "seed001" : plant;
}

std::map<std::string, AxisDrive> open_axis_drives(const std::map<std::string, drive::DriveSpec>& specs,
                                                  const std::map<std::string, drive::AxisLimits>& flag_limits,
                                                  const DriveSettings& settings) {
  std::map<std::string, AxisDrive> drives;
  for (const auto& [axis, spec] : specs) {
    AxisDrive entry;
    entry.spec = spec;
    const auto flags = flag_limits.count(axis) ? flag_limits.at(axis) : drive::AxisLimits{};
    if (spec.kind == drive::DriveSpec::Kind::simulated && plant::is_file_plant(spec.plant())) {
      // An FMU's or a plugin's model has no rating netmc knows: its limits come from the flags.
      entry.limits = flags;
      require_limits(entry.limits, axis, spec, "a plant read from a file");
    } else if (spec.kind == drive::DriveSpec::Kind::simulated) {
      // Overrides must name the plant's keys: checked now, not at the first job.
      const auto keys = plant::plant_parameters(spec.plant());
      for (const auto& [key, value] : spec.plant_overrides()) {
        bool known = false;
        for (const auto& parameter : keys) known = known || parameter.key == key;
        if (!known) {
          throw std::invalid_argument("--drive " + axis + "=" + spec.describe() + ": plant " + spec.plant() +
                                      " has no parameter '" + key.substr(0, 64) + "' (netmc sim --plant-parameters " +
                                      spec.plant() + " lists them)");
        }
      }
      entry.limits = flags.or_else(rating_limits(spec.plant()));
    } else {
      const std::string flag = "--drive " + axis + "=" + spec.describe().substr(0, 120);
      try {
        entry.hardware = open_hardware(spec);
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument(flag + ": " + error.what());
      } catch (const drive::DriveError& error) {
        throw drive::DriveError(flag + ": " + error.what());
      }
      entry.hardware->write_quick_stop_deceleration(settings.quick_stop_deceleration_m_s2);
      entry.limits = flags.or_else(entry.hardware->configured_limits());
      require_limits(entry.limits, axis, spec, "a drive that is not simulated");
    }
    entry.limits = entry.limits.with_default_following_error();
    entry.limits.validate();
    drives.emplace(axis, std::move(entry));
  }
  return drives;
}

netmc::v1::JobSpec with_node_overrides(netmc::v1::JobSpec spec, const std::string& axis, const AxisDrive& drive) {
  const auto overrides = drive.spec.plant_overrides();
  if (overrides.empty()) return spec;
  netmc::v1::PlantAxisSettings* settings = nullptr;
  for (auto& candidate : *spec.mutable_plant_axes()) {
    if (candidate.axis() == axis) settings = &candidate;
  }
  if (!settings) {
    settings = spec.add_plant_axes();
    settings->set_axis(axis);
  }
  for (const auto& [key, value] : overrides) {
    auto* parameter = settings->add_parameters();
    parameter->set_key(key);
    parameter->set_value(value);
  }
  return spec;
}

std::shared_ptr<drive::Drive> job_drive(const AxisDrive& drive, const sim::ContourJob& job, std::size_t index,
                                        const DriveSettings& settings) {
  if (drive.hardware) return drive.hardware;
  auto simulated = sim::AxisEndpoint::simulated_drive(job, index);
  simulated->write_quick_stop_deceleration(settings.quick_stop_deceleration_m_s2);
  return simulated;
}

}  // namespace netmc::axis
