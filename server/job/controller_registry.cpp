#include "server/job/controller_registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "control/contour_error/contour_error_estimator.hpp"
#include "control/cross_coupling/contouring_controller.hpp"
#include "control/group/planar_contour_group.hpp"
#include "server/plugins/component_plugin_spec.hpp"
#include "server/plugins/loaded_component_plugin.hpp"

#include "server/job/quantity_text.hpp"

namespace netmc::job {
namespace {

constexpr std::string_view kPluginPrefix = "plugin:";

const char* role_name(ControllerRole role) {
  switch (role) {
    case ControllerRole::axis: return "axis law";
    case ControllerRole::compensator: return "contour compensator";
    case ControllerRole::group: return "group law";
    case ControllerRole::tracking: return "single-axis law";
  }
  return "?";
}

// Errors of the laws (their constructors check their gains) read "controller: ...".
template <class Build>
auto as_controller_error(Build&& build) {
  try {
    return build();
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    if (message.rfind("controller", 0) == 0) throw;
    throw std::invalid_argument("controller: " + message);
  }
}

}  // namespace

ControllerRegistry& ControllerRegistry::global() {
  static ControllerRegistry registry = [] {
    ControllerRegistry built_in;
    // One line per family file (server/job/controllers/).
#define NETMC_CONTROLLER(name) register_##name(built_in);
#include "server/job/controllers/registered_controllers.inc"
#undef NETMC_CONTROLLER
    return built_in;
  }();
  return registry;
}

void ControllerRegistry::add(GainGroup group) {
  if (gain_group(group.name)) throw std::logic_error("gains group " + group.name + " registered twice");
  groups_.push_back(std::move(group));
}

void ControllerRegistry::add(ControllerFamily family) {
  for (const auto& name : family.names) {
    if (this->family(name)) throw std::logic_error("controller " + name + " registered twice");
  }
  for (const auto& group : family.gain_groups) {
    if (!gain_group(group)) throw std::logic_error("controller " + family.names.front() + ": no gains group " + group);
  }
  // Defaults that work somewhere, or the keys without which the family is refused.
  if (family.plants.empty() && (family.required_gains.empty() || family.gain_groups.empty())) {
    throw std::logic_error("controller " + family.names.front() + ": no plant its defaults are tuned for and no required gains");
  }
  families_.push_back(std::move(family));
}

const GainGroup* ControllerRegistry::gain_group(std::string_view name) const {
  for (const auto& group : groups_) {
    if (group.name == name) return &group;
  }
  return nullptr;
}

const ControllerFamily* ControllerRegistry::family(std::string_view name) const {
  for (const auto& family : families_) {
    if (std::find(family.names.begin(), family.names.end(), name) != family.names.end()) return &family;
  }
  return nullptr;
}

std::string ControllerRegistry::names_help() const {
  std::vector<std::string> axis, compensators, groups, tracking;
  for (const auto& family : families_) {
    auto& list = family.role == ControllerRole::axis          ? axis
                 : family.role == ControllerRole::compensator ? compensators
                 : family.role == ControllerRole::tracking    ? tracking
                                                              : groups;
    for (const auto& name : family.names) list.push_back(family.takes_compensator ? name + "[+COMPENSATOR]" : name);
  }
  return fmt::format("AXIS[+COMPENSATOR] with AXIS one of {} and COMPENSATOR one of {}; {}; one axis "
                     "(--trajectory multi-sine): {}; plugin:PATH.so[:KEY=VALUE,...] (netmc sim --list-controllers)",
                     join_list(axis), join_list(compensators), join_list(groups), join_list(tracking));
}

std::vector<std::string> ControllerRegistry::single_axis_names() const {
  std::vector<std::string> names;
  for (const auto& family : families_) {
    if (family.role == ControllerRole::tracking) names.insert(names.end(), family.names.begin(), family.names.end());
  }
  return names;
}

std::string ControllerRegistry::markdown_table() const {
  std::string table =
      "| controller | role | gains | source | defaults tuned for | what it is |\n"
      "| --- | --- | --- | --- | --- | --- |\n";
  for (const auto& family : families_) {
    std::vector<std::string> flags;
    for (const auto& group_name : family.gain_groups) flags.push_back("`" + gain_group(group_name)->flag + "`");
    std::vector<std::string> names;
    for (const auto& name : family.names) names.push_back("`" + name + "`");
    table += fmt::format("| {} | {} | {} | {} | {} | {} |\n", join_list(names), role_name(family.role),
                         flags.empty() ? "none" : join_list(flags), family.source,
                         family.plants.empty() ? "none: needs `" + gain_group(family.gain_groups.front())->flag + " " +
                                                     family.required_gains.front() + "=`"
                                               : join_list(family.plants),
                         family.summary);
  }
  return table;
}

namespace {

// A family whose defaults do not make a working controller runs only with the keys it names.
void check_required_gains(const netmc::v1::ControllerSpec& spec, const ControllerFamily& family,
                          const std::vector<std::string>& axis_names) {
  if (family.required_gains.empty()) return;
  const GainsReader gains(spec, axis_names);
  const std::string& group = family.gain_groups.front();
  for (const auto& key : family.required_gains) {
    double number = 0.0;
    if (gains.read(group, key, number) || gains.choice(group, key) || gains.list(group, key)) continue;
    throw std::invalid_argument("controller: " + family.names.front() + " needs " + gains.field(group, key) +
                                " (" + ControllerRegistry::global().gain_group(group)->flag + " " + key +
                                "=...): " + family.required_why);
  }
}

// Errors of a plugin's name and settings read "controller: plugin: ...".
template <class Build>
auto as_plugin_error(Build&& build) {
  try {
    return build();
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(std::string("controller: ") + error.what());
  }
}

}  // namespace

ControllerFactory ControllerRegistry::resolve_plugin(const netmc::v1::ControllerSpec& spec,
                                                     const sim::JobReference& reference,
                                                     const std::vector<std::string>& axis_names,
                                                     double sample_period_s,
                                                     const ControllerPluginPolicy& policy) const {
  // plugin:PATH.so[:KEY=VALUE,...][+COMPENSATOR]: an axis law of the researcher's own, one object
  // per axis, composed with a contour compensator as the built-in axis laws are.
  std::string text = spec.name().substr(kPluginPrefix.size());
  const ControllerFamily* compensator = nullptr;
  if (const std::size_t plus = text.rfind('+'); plus != std::string::npos) {
    const ControllerFamily* candidate = family(std::string_view(text).substr(plus + 1));
    if (candidate && candidate->role == ControllerRole::compensator) {
      compensator = candidate;
      text.resize(plus);
    }
  }
  const plugins::ComponentPluginSpec parsed = as_plugin_error([&] { return plugins::parse_component_plugin_spec(text); });
  if (sim::reference_dimension(reference) != 2) {
    throw std::invalid_argument("controller: a plugin's axis law runs two-axis contours only");
  }
  // AXIS.KEY=VALUE: that axis's own setting, over KEY=VALUE.
  plugins::PluginSettings common;
  std::vector<plugins::PluginSettings> own(axis_names.size());
  for (const auto& [key, value] : parsed.settings) {
    bool placed = false;
    for (std::size_t axis = 0; axis < axis_names.size() && !placed; ++axis) {
      const std::string& prefix = axis_names[axis];
      if (key.size() > prefix.size() + 1 && key.compare(0, prefix.size(), prefix) == 0 && key[prefix.size()] == '.') {
        own[axis][key.substr(prefix.size() + 1)] = value;
        placed = true;
      }
    }
    if (!placed) common[key] = value;
  }
  if (policy.allowed &&
      std::find(policy.allowed->begin(), policy.allowed->end(), parsed.path) == policy.allowed->end()) {
    throw std::invalid_argument("controller: plugin " + parsed.path.substr(0, 200) +
                                " is not a file this server loads (netmc-server --allow-plugin PATH)");
  }
  if (!policy.load) {
    return []() -> std::unique_ptr<control::GroupController> {
      throw std::logic_error("controller: a plugin controller runs on the server, not in this process");
    };
  }
  const auto loaded = as_plugin_error([&] { return plugins::LoadedComponentPlugin::load(parsed.path); });
  if (!loaded->provides_axis_controller()) {
    throw std::invalid_argument("controller: plugin " + parsed.path.substr(0, 200) +
                                " provides no axis controller (a plant only?)");
  }
  struct Recipe {
    netmc::v1::ControllerSpec spec;
    sim::JobReference reference;
    std::vector<std::string> axis_names;
    double sample_period_s;
    std::shared_ptr<const plugins::LoadedComponentPlugin> plugin;
    plugins::PluginSettings common;
    std::vector<plugins::PluginSettings> own;
    const ControllerFamily* compensator;
  };
  auto recipe = std::make_shared<const Recipe>(
      Recipe{spec, reference, axis_names, sample_period_s, loaded, common, own, compensator});
  ControllerFactory factory = [recipe]() -> std::unique_ptr<control::GroupController> {
    const GainsReader gains(recipe->spec, recipe->axis_names);
    const ControllerContext context{gains, recipe->sample_period_s, recipe->reference, recipe->spec.estimator()};
    return as_controller_error([&]() -> std::unique_ptr<control::GroupController> {
      std::unique_ptr<control::ContourCompensator> compensation =
          recipe->compensator ? recipe->compensator->make_compensator(context)
                              : std::make_unique<control::NoContourCompensation>();
      const auto axis_law = [&](std::size_t axis) {
        plugins::PluginSettings settings = recipe->common;
        for (const auto& [key, value] : recipe->own[axis]) settings[key] = value;
        return recipe->plugin->make_axis_controller(settings, axis, recipe->sample_period_s);
      };
      const auto trajectory = std::get<std::shared_ptr<const control::ReferenceTrajectory>>(recipe->reference);
      auto controller = std::make_unique<control::ContouringController>(
          axis_law(0), axis_law(1),
          control::make_contour_error_estimator(context.estimator.empty() ? "curvature" : context.estimator,
                                                trajectory),
          std::move(compensation));
      return std::make_unique<control::PlanarGroupController>(std::move(controller));
    });
  };
  factory();  // the plugin's factories refuse their settings now, not at the first run
  return factory;
}

std::vector<std::string> ControllerRegistry::predicting_laws() const {
  std::vector<std::string> names;
  for (const auto& candidate : families_) {
    if (candidate.prediction_model) names.insert(names.end(), candidate.names.begin(), candidate.names.end());
  }
  return names;
}

std::optional<std::vector<control::PredictionModel>> ControllerRegistry::prediction_models(const netmc::v1::ControllerSpec& spec,
                                                                          const sim::JobReference& reference,
                                                                          const std::vector<std::string>& axis_names,
                                                                          double sample_period_s) const {
  const std::string& name = spec.name();
  const ControllerFamily* head = family(name);
  if (!head && name.rfind(kPluginPrefix, 0) != 0) head = family(std::string_view(name).substr(0, name.find('+')));
  if (!head || !head->prediction_model) return std::nullopt;
  const GainsReader gains(spec, axis_names);
  const ControllerContext context{gains, sample_period_s, reference, spec.estimator()};
  std::vector<control::PredictionModel> models;
  for (std::size_t axis = 0; axis < axis_names.size(); ++axis) models.push_back(head->prediction_model(context, axis));
  return models;
}

ControllerFactory ControllerRegistry::resolve(const netmc::v1::ControllerSpec& spec, const sim::JobReference& reference,
                                              const std::vector<std::string>& axis_names, double sample_period_s,
                                              const ControllerPluginPolicy& plugins) const {
  std::vector<const GainGroup*> groups;
  for (const auto& group : groups_) groups.push_back(&group);
  check_gains(spec, groups, axis_names);
  const std::string name = spec.name();
  if (name.rfind(kPluginPrefix, 0) == 0) return resolve_plugin(spec, reference, axis_names, sample_period_s, plugins);
  if (!spec.estimator().empty()) {
    const auto known = control::contour_error_estimator_names();
    if (std::find(known.begin(), known.end(), spec.estimator()) == known.end()) {
      throw std::invalid_argument("controller.estimator: expected one of " + join_list(known) + ", got '" +
                                  spec.estimator().substr(0, 64) + "'");
    }
  }
  const ControllerFamily* whole = family(name);
  const ControllerFamily* head = whole;
  const ControllerFamily* compensator = nullptr;
  const std::size_t plus = name.find('+');
  if (!whole && plus != std::string::npos) {
    head = family(std::string_view(name).substr(0, plus));
    compensator = family(std::string_view(name).substr(plus + 1));
    if (!compensator || compensator->role != ControllerRole::compensator) head = nullptr;
  }
  if (!head || head->role == ControllerRole::compensator ||
      (compensator && head->role != ControllerRole::axis && !head->takes_compensator)) {
    throw std::invalid_argument("controller: unknown name '" + name.substr(0, 80) + "' (expected " + names_help() + ")");
  }
  const std::size_t dimension = sim::reference_dimension(reference);
  const bool tracking = dimension == 1;
  if (tracking != (head->role == ControllerRole::tracking)) {
    throw std::invalid_argument(tracking ? "controller: a single-axis job runs a single-axis law, got '" + name + "'"
                                         : "controller: " + name + " is a single-axis law: it runs --trajectory multi-sine");
  }
  if (head->role == ControllerRole::axis && dimension != 2) {
    throw std::invalid_argument("controller: " + name + " runs two-axis contours only");
  }
  check_required_gains(spec, *head, axis_names);
  // The factory keeps what it builds from.
  struct Recipe {
    netmc::v1::ControllerSpec spec;
    sim::JobReference reference;
    std::vector<std::string> axis_names;
    double sample_period_s;
    std::string name;
    const ControllerFamily* head;
    const ControllerFamily* compensator;
  };
  auto recipe = std::make_shared<const Recipe>(
      Recipe{spec, reference, axis_names, sample_period_s, name, head, compensator});
  ControllerFactory factory = [recipe]() -> std::unique_ptr<control::GroupController> {
    const GainsReader gains(recipe->spec, recipe->axis_names);
    const ControllerContext context{gains, recipe->sample_period_s, recipe->reference, recipe->spec.estimator()};
    return as_controller_error([&]() -> std::unique_ptr<control::GroupController> {
      std::unique_ptr<control::ContourCompensator> compensation =
          recipe->compensator ? recipe->compensator->make_compensator(context) : nullptr;
      if (recipe->head->role != ControllerRole::axis) {
        return recipe->head->make_group(context, recipe->name, std::move(compensation));
      }
      if (!compensation) compensation = std::make_unique<control::NoContourCompensation>();
      const auto trajectory = std::get<std::shared_ptr<const control::ReferenceTrajectory>>(recipe->reference);
      auto controller = std::make_unique<control::ContouringController>(
          recipe->head->make_axis(context, 0), recipe->head->make_axis(context, 1),
          control::make_contour_error_estimator(context.estimator.empty() ? "curvature" : context.estimator,
                                                trajectory),
          std::move(compensation));
      return std::make_unique<control::PlanarGroupController>(std::move(controller));
    });
  };
  factory();  // what only the laws can check, checked now
  return factory;
}

}  // namespace netmc::job
