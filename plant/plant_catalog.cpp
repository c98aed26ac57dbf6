#include "plant/plant_catalog.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "plant/dead_zone_input.hpp"
#include "plant/plant_registry.hpp"
#include "plant/plant_settings.hpp"

namespace netmc::plant {
namespace {

const char* const kAxisLabels[] = {"X", "Y", "Z"};

}  // namespace

bool is_file_plant(std::string_view name) {
  return name.substr(0, 4) == "fmu:" || name.substr(0, 7) == "plugin:";
}

std::vector<std::string> plant_names() {
  std::vector<std::string> names;
  for (const auto& model : PlantRegistry::global().models()) names.push_back(model.name);
  return names;
}

std::vector<PlantParameter> plant_parameters(std::string_view name) {
  const PlantModel& model = PlantRegistry::global().at(name);
  std::vector<PlantParameter> out = model.parameters;
  if (!model.own_dead_zone) {
    for (const auto& p : describe_settings(dead_zone_settings({}, model.input_unit))) out.push_back(p);
  }
  return out;
}

PlantRating plant_rating(std::string_view name) { return PlantRegistry::global().at(name).rating; }

std::string plant_input_unit(std::string_view name) { return PlantRegistry::global().at(name).input_unit; }

AxisSet make_plant_set(std::string_view name, std::size_t axis_count, const std::vector<AxisOverrides>& overrides) {
  const PlantModel& model = PlantRegistry::global().at(name);
  if (axis_count < 1 || axis_count > 3) {
    throw std::invalid_argument("plant: axis_count must be 1, 2 or 3 (got " +
                                std::to_string(axis_count) + ")");
  }
  if (overrides.size() > axis_count) {
    throw std::invalid_argument("plant: overrides for " + std::to_string(overrides.size()) + " axes, the set has " +
                                std::to_string(axis_count));
  }
  AxisSet set;
  set.description = model.name + ": " + model.title;
  for (std::size_t axis = 0; axis < axis_count; ++axis) {
    // A dead zone in front of the axis (every plant but one whose model holds its own): its keys
    // apply to a DeadZoneInput around the plant, the rest to the plant.
    AxisOverrides plant_changes;
    DeadZoneParameters dead_zone;
    bool has_dead_zone = false;
    if (axis < overrides.size()) {
      plant_changes.disturbance = overrides[axis].disturbance;
      const auto keys = dead_zone_settings({}, "");
      for (const auto& [key, value] : overrides[axis].parameters) {
        const auto it = std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.key == key; });
        if (model.own_dead_zone || it == keys.end()) {
          plant_changes.parameters.emplace_back(key, value);
        } else if (!std::isfinite(value)) {
          throw std::invalid_argument("plant: " + key + " must be a finite number (got " + std::to_string(value) + ")");
        } else {
          it->apply(dead_zone, value);
          has_dead_zone = true;
        }
      }
    }
    std::unique_ptr<AxisPlant> plant = model.make_axis(axis, axis < overrides.size() ? &plant_changes : nullptr);
    if (has_dead_zone) {
      try {
        plant = std::make_unique<DeadZoneInput>(dead_zone, std::move(plant));
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument(std::string("plant: dead zone: ") + error.what());
      }
    }
    plant->reset(0.0, 0.0);
    set.description += std::string(" | ") + kAxisLabels[axis] + ": " + plant->describe();
    set.axes.push_back(std::move(plant));
  }
  return set;
}

}  // namespace netmc::plant
