#pragma once
// A plugin's axis controller or plant as netmc holds it: the plugin's object together with a
// reference to the loaded plugin, so the library (the object's code and vtable) stays loaded as
// long as the object or any clone of it lives. Every call goes straight to the plugin's object;
// describe() comes back bounded and printable. The object is destroyed before the reference is
// released (member order), so its destructor still has its code.

#include <memory>
#include <string>

#include "control/axis/axis_controller.hpp"
#include "plant/axis_plant.hpp"

namespace netmc::plugins {

class LoadedComponentPlugin;

class PluginAxisController final : public control::AxisController {
 public:
  // `controller` is not null.
  PluginAxisController(std::shared_ptr<const LoadedComponentPlugin> plugin,
                       std::unique_ptr<control::AxisController> controller);

  void reset(double position) override { controller_->reset(position); }
  double command(double reference, double measured_position) const override {
    return controller_->command(reference, measured_position);
  }
  void commit(double reference, double measured_position, double own_command, double sent_command) override {
    controller_->commit(reference, measured_position, own_command, sent_command);
  }
  // std::logic_error naming the plugin when its clone() gives nothing.
  std::unique_ptr<control::AxisController> clone() const override;
  std::string describe() const override;

 private:
  std::shared_ptr<const LoadedComponentPlugin> plugin_;  // first in, last out
  std::unique_ptr<control::AxisController> controller_;
};

class PluginAxisPlant final : public plant::AxisPlant {
 public:
  // `axis` is not null.
  PluginAxisPlant(std::shared_ptr<const LoadedComponentPlugin> plugin, std::unique_ptr<plant::AxisPlant> axis);

  void reset(double position, double velocity) override { axis_->reset(position, velocity); }
  void advance(double duration_s, double input) override { axis_->advance(duration_s, input); }
  double position() const override { return axis_->position(); }
  double velocity() const override { return axis_->velocity(); }
  double time() const override { return axis_->time(); }
  std::unique_ptr<plant::AxisPlant> clone() const override;
  std::string describe() const override;

 private:
  std::shared_ptr<const LoadedComponentPlugin> plugin_;  // first in, last out
  std::unique_ptr<plant::AxisPlant> axis_;
};

}  // namespace netmc::plugins
