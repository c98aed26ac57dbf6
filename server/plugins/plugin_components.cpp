#include "server/plugins/plugin_components.hpp"

#include <stdexcept>
#include <utility>

#include "server/plugins/component_plugin_text.hpp"
#include "server/plugins/loaded_component_plugin.hpp"

namespace netmc::plugins {

PluginAxisController::PluginAxisController(std::shared_ptr<const LoadedComponentPlugin> plugin,
                                           std::unique_ptr<control::AxisController> controller)
    : plugin_(std::move(plugin)), controller_(std::move(controller)) {}

std::unique_ptr<control::AxisController> PluginAxisController::clone() const {
  auto copy = controller_->clone();
  if (!copy) throw std::logic_error("plugin " + plugin_->path() + ": its axis controller's clone() gave nothing");
  return std::make_unique<PluginAxisController>(plugin_, std::move(copy));
}

std::string PluginAxisController::describe() const {
  return plugin_text(controller_->describe(), "(no description)");
}

PluginAxisPlant::PluginAxisPlant(std::shared_ptr<const LoadedComponentPlugin> plugin,
                                 std::unique_ptr<plant::AxisPlant> axis)
    : plugin_(std::move(plugin)), axis_(std::move(axis)) {}

std::unique_ptr<plant::AxisPlant> PluginAxisPlant::clone() const {
  auto copy = axis_->clone();
  if (!copy) throw std::logic_error("plugin " + plugin_->path() + ": its plant's clone() gave nothing");
  return std::make_unique<PluginAxisPlant>(plugin_, std::move(copy));
}

std::string PluginAxisPlant::describe() const { return plugin_text(axis_->describe(), "(no description)"); }

}  // namespace netmc::plugins
