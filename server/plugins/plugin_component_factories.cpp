#include "server/plugins/plugin_component_factories.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "server/plugins/loaded_component_plugin.hpp"

namespace netmc::plugins {
namespace {

// "X", "Y", "Z" for axes 0, 1, 2; the index beyond.
std::string axis_label(std::size_t axis_index) {
  constexpr const char* kLabels[] = {"X", "Y", "Z"};
  return axis_index < 3 ? kLabels[axis_index] : std::to_string(axis_index);
}

// The axis's own key=value pairs, checked as the spec's are, laid over `settings` in order.
template <typename Pairs>
PluginSettings with_axis_settings(PluginSettings settings, const Pairs& over, std::size_t axis_index) {
  for (const auto& [key, value] : over) {
    if (!is_component_plugin_key(key)) {
      throw std::invalid_argument("plugin: axis " + axis_label(axis_index) + ": key '" +
                                  key.substr(0, kMaxComponentPluginKeyLength) +
                                  "' is empty, too long or has a character other than A-Z a-z 0-9 _ . -");
    }
    if (!std::isfinite(value)) {
      throw std::invalid_argument("plugin: axis " + axis_label(axis_index) + ": " + key + " must be finite (got " +
                                  std::to_string(value) + ")");
    }
    settings[key] = value;
  }
  return settings;
}

}  // namespace

plant::AxisSet make_plugin_plant_set(std::string_view text, std::size_t axis_count,
                                     const std::vector<plant::AxisOverrides>& overrides) {
  const ComponentPluginSpec spec = parse_component_plugin_spec(std::string(text));
  if (axis_count < 1 || axis_count > 3) {
    throw std::invalid_argument("plant: axis_count must be 1, 2 or 3 (got " + std::to_string(axis_count) + ")");
  }
  if (overrides.size() > axis_count) {
    throw std::invalid_argument("plant: overrides for " + std::to_string(overrides.size()) + " axes, the set has " +
                                std::to_string(axis_count));
  }
  for (std::size_t axis = 0; axis < overrides.size(); ++axis) {
    if (!overrides[axis].disturbance.is_zero()) {
      throw std::invalid_argument("plugin " + spec.path + ": axis " + axis_label(axis) +
                                  " has a disturbance; a plugin plant takes none from netmc (model it in the plugin)");
    }
  }
  const auto plugin = LoadedComponentPlugin::load(spec.path);
  plant::AxisSet set;
  set.description = "plugin:" + spec.path + " (" + plugin->description() + ")";
  for (std::size_t axis = 0; axis < axis_count; ++axis) {
    const PluginSettings settings =
        axis < overrides.size() ? with_axis_settings(spec.settings, overrides[axis].parameters, axis) : spec.settings;
    auto plant = plugin->make_plant(settings, axis);
    plant->reset(0.0, 0.0);
    set.description += " | " + axis_label(axis) + ": " + plant->describe();
    set.axes.push_back(std::move(plant));
  }
  return set;
}

std::unique_ptr<control::AxisController> make_plugin_axis_controller(std::string_view text, std::size_t axis_index,
                                                                     double sample_period_s,
                                                                     const PluginSettings& axis_settings) {
  const ComponentPluginSpec spec = parse_component_plugin_spec(std::string(text));
  const PluginSettings settings = with_axis_settings(spec.settings, axis_settings, axis_index);
  return LoadedComponentPlugin::load(spec.path)->make_axis_controller(settings, axis_index, sample_period_s);
}

}  // namespace netmc::plugins
