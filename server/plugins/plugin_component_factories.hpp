#pragma once
// What the controller and plant registries call for `plugin:PATH.so[:key=value,...]`: the text
// after `plugin:` parsed (component_plugin_spec.hpp), the plugin loaded and checked
// (loaded_component_plugin.hpp), and its objects made for each axis with the spec's settings,
// then the axis's own over them (the later value of a key wins). Every refusal is one
// std::invalid_argument.

#include <cstddef>
#include <memory>
#include <string_view>
#include <vector>

#include "control/axis/axis_controller.hpp"
#include "plant/plant_catalog.hpp"
#include "server/plugins/component_plugin_spec.hpp"

namespace netmc::plugins {

// One plant per axis from the plugin's make_plant, each reset to rest at 0. axis_count is 1, 2
// or 3; `overrides` has at most axis_count entries (axis 0 first; missing ones change nothing):
// overrides[i].parameters go to axis i's settings after the spec's, and a non-zero
// overrides[i].disturbance is refused (a plugin plant models its own disturbances).
// description: "plugin:PATH (what the plugin says) | X: ... | Y: ...".
plant::AxisSet make_plugin_plant_set(std::string_view text, std::size_t axis_count,
                                     const std::vector<plant::AxisOverrides>& overrides);

// The loop of axis `axis_index` (0 = X) from the plugin's make_axis_controller, with
// `axis_settings` after the spec's.
std::unique_ptr<control::AxisController> make_plugin_axis_controller(std::string_view text, std::size_t axis_index,
                                                                     double sample_period_s,
                                                                     const PluginSettings& axis_settings = {});

}  // namespace netmc::plugins
