#include "server/job/plant_source.hpp"

#include <memory>
#include <stdexcept>

#include "server/fmu/fmu_plant_set.hpp"
#include "server/plugins/plugin_component_factories.hpp"

namespace netmc::job {
namespace {

constexpr std::string_view kFmuPrefix = "fmu:";
constexpr std::string_view kPluginPrefix = "plugin:";

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

// An axis whose model runs in another process: anything that would simulate it is a bug.
class RemoteAxisPlant final : public plant::AxisPlant {
 public:
  explicit RemoteAxisPlant(std::string name) : name_(std::move(name)) {}
  void reset(double, double) override { refuse(); }
  void advance(double, double) override { refuse(); }
  double position() const override { refuse(); }
  double velocity() const override { refuse(); }
  double time() const override { refuse(); }
  std::unique_ptr<plant::AxisPlant> clone() const override { return std::make_unique<RemoteAxisPlant>(*this); }
  std::string describe() const override { return name_ + " (held by the axis node)"; }

 private:
  [[noreturn]] void refuse() const {
    throw std::logic_error("plant " + name_ + " runs on its axis node, not in this process");
  }
  std::string name_;
};

}  // namespace

plant::AxisSet make_job_plant_set(std::string_view name, std::size_t axis_count,
                                  const std::vector<plant::AxisOverrides>& overrides) {
  if (starts_with(name, kFmuPrefix)) {
    return plant::fmu::make_fmu_plant_set(name.substr(kFmuPrefix.size()), axis_count, overrides);
  }
  if (starts_with(name, kPluginPrefix)) {
    return plugins::make_plugin_plant_set(name.substr(kPluginPrefix.size()), axis_count, overrides);
  }
  return plant::make_plant_set(name, axis_count, overrides);
}

std::vector<plant::PlantParameter> job_plant_parameters(std::string_view name) {
  if (starts_with(name, kFmuPrefix)) return plant::fmu::summarize_fmu_plant(name.substr(kFmuPrefix.size())).parameters;
  if (starts_with(name, kPluginPrefix)) return {};
  return plant::plant_parameters(name);
}

std::string job_plant_input_unit(std::string_view name) {
  if (starts_with(name, kFmuPrefix)) {
    const std::string unit = plant::fmu::summarize_fmu_plant(name.substr(kFmuPrefix.size())).input_unit;
    return unit.empty() ? "input" : unit;
  }
  if (starts_with(name, kPluginPrefix)) return "input";
  return plant::plant_input_unit(name);
}

plant::AxisSet remote_plant_set(std::string_view name, std::size_t axis_count) {
  plant::AxisSet set;
  for (std::size_t i = 0; i < axis_count; ++i) set.axes.push_back(std::make_unique<RemoteAxisPlant>(std::string(name)));
  set.description = std::string(name) + " (held by the axis nodes)";
  return set;
}

}  // namespace netmc::job
