#include "server/fmu/fmu_plant_set.hpp"

#include <array>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "server/fmu/fmu_axis_plant.hpp"
#include "server/fmu/fmu_model.hpp"
#include "server/fmu/fmu_plant_options.hpp"
#include "server/fmu/model_description.hpp"
#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {
namespace {

constexpr std::size_t kMaxAxes = 3;
constexpr std::array<std::string_view, kMaxAxes> kAxisNames{"x", "y", "z"};

// The checks of the variables an option names, against one FMU's description.
class VariableResolver {
 public:
  VariableResolver(const ModelDescription& description, std::string path)
      : description_(description), path_(std::move(path)) {}

  // Where a user finds the names an FMU has: `mass=2.5` of another tool's FMU is a guess.
  std::string no_variable_hint() const {
    return " (netmc sim --plant-parameters fmu:" + printable_text(path_) + " lists the parameters it has)";
  }

  [[noreturn]] void refuse(const std::string& why) const {
    throw std::invalid_argument("fmu " + printable_text(path_) + ": " + why);
  }

  const ScalarVariable& existing(const std::string& name, const std::string& option) const {
    const ScalarVariable* v = description_.find(name);
    if (v == nullptr) refuse(option + ": the FMU has no variable " + quoted(name) + no_variable_hint());
    if (v->type != VariableType::real) {
      refuse(option + ": variable " + quoted(name) + " is " + std::string(variable_type_name(v->type)) +
             ", netmc needs a Real");
    }
    return *v;
  }

  RealVariable with_causality(const std::string& name, const std::string& option, Causality wanted) const {
    const ScalarVariable& v = existing(name, option);
    if (v.causality != wanted) {
      refuse(option + ": variable " + quoted(name) + " has causality " + std::string(causality_name(v.causality)) +
             ", expected " + std::string(causality_name(wanted)));
    }
    return {v.name, v.value_reference};
  }

  RealVariable parameter(const std::string& name, const std::string& option) const {
    const ScalarVariable& v = existing(name, option);
    if (v.causality != Causality::parameter ||
        (v.variability != Variability::fixed && v.variability != Variability::tunable)) {
      refuse(option + ": variable " + quoted(name) + " has causality " + std::string(causality_name(v.causality)) +
             " and variability " + std::string(variability_name(v.variability)) +
             ", expected a parameter (fixed or tunable)");
    }
    return {v.name, v.value_reference};
  }

  // A variable that takes a start value before initialisation (FMI 2.0, 2.2.7: a parameter, or
  // a state-like variable with an exact or approximate start).
  RealVariable start_variable(const std::string& name, const std::string& option) const {
    const ScalarVariable& v = existing(name, option);
    const bool parameter = v.causality == Causality::parameter &&
                           (v.variability == Variability::fixed || v.variability == Variability::tunable);
    const bool state = (v.causality == Causality::local || v.causality == Causality::output) &&
                       v.variability == Variability::continuous && v.start.has_value() &&
                       v.initial != Initial::calculated;
    if (!parameter && !state) {
      refuse(option + ": variable " + quoted(name) + " (causality " + std::string(causality_name(v.causality)) +
             ", variability " + std::string(variability_name(v.variability)) +
             ") cannot take a start value: expected a parameter, or a continuous state with a start value");
    }
    return {v.name, v.value_reference};
  }

  bool has(const std::string& name) const { return description_.find(name) != nullptr; }

 private:
  const ModelDescription& description_;
  std::string path_;
};

// The axis a qualified key names ("1.b", "y.b"), or empty.
std::optional<std::size_t> axis_of(std::string_view qualifier) {
  for (std::size_t i = 0; i < kMaxAxes; ++i) {
    if (qualifier == std::to_string(i) || qualifier == kAxisNames[i]) return i;
    if (qualifier.size() == 1 && qualifier[0] == kAxisNames[i][0] - 'a' + 'A') return i;
  }
  return std::nullopt;
}

// One option-level parameter: for every axis (axis empty) or one.
struct ResolvedParameter {
  std::optional<std::size_t> axis;
  RealVariable variable;
  double value = 0.0;
};

std::vector<ResolvedParameter> resolve_parameters(const FmuPlantOptions& options, const VariableResolver& resolver,
                                                  std::size_t axis_count) {
  std::vector<ResolvedParameter> out;
  for (const auto& [key, value] : options.parameters) {
    const std::string option = "option '" + key + "'";
    // A variable of the FMU by the whole key first: Modelica names have dots of their own.
    if (resolver.has(key)) {
      out.push_back({std::nullopt, resolver.parameter(key, option), value});
      continue;
    }
    const std::size_t dot = key.find('.');
    const auto axis = dot == std::string::npos ? std::nullopt : axis_of(std::string_view(key).substr(0, dot));
    if (!axis) resolver.refuse(option + ": the FMU has no variable " + quoted(key) + resolver.no_variable_hint());
    if (*axis >= axis_count) {
      resolver.refuse(option + ": names axis " + std::to_string(*axis) + " of a set of " + std::to_string(axis_count) +
                      " axes");
    }
    out.push_back({axis, resolver.parameter(key.substr(dot + 1), option), value});
  }
  return out;
}

}  // namespace

bool is_fmu_plant(std::string_view plant_name) { return plant_name.substr(0, 4) == "fmu:"; }

AxisSet make_fmu_plant_set(std::string_view text, std::size_t axis_count, const std::vector<AxisOverrides>& overrides) {
  const FmuPlantOptions options = parse_fmu_plant_options(text);
  const std::string where = "fmu " + printable_text(options.path);
  if (axis_count < 1 || axis_count > kMaxAxes) {
    throw std::invalid_argument(where + ": axis_count must be 1, 2 or 3 (got " + std::to_string(axis_count) + ")");
  }
  if (overrides.size() > axis_count) {
    throw std::invalid_argument(where + ": " + std::to_string(overrides.size()) + " axis overrides for " +
                                std::to_string(axis_count) + " axes");
  }
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    if (!overrides[i].disturbance.is_zero()) {
      throw std::invalid_argument(where + ": axis " + std::to_string(i) +
                                  ": a disturbance is not supported for FMU plants (model it inside the FMU)");
    }
  }
  const std::shared_ptr<FmuModel> model = FmuModel::load(options.path);
  const ModelDescription& description = model->description();
  const VariableResolver resolver(description, options.path);
  if (description.co_simulation.can_be_instantiated_only_once_per_process && axis_count > 1) {
    resolver.refuse("the model declares canBeInstantiatedOnlyOncePerProcess: it can run one axis, not " +
                    std::to_string(axis_count));
  }

  FmuAxisSetup common;
  common.model = model;
  common.options_text = std::string(text.substr(0, 4) == "fmu:" ? text.substr(4) : text);
  const auto named = [](const std::string& key, const std::string& value, bool given) {
    return "option '" + key + "=" + value + "'" + (given ? "" : " (the default)");
  };
  const std::string input = options.input.value_or(kDefaultFmuInput);
  common.input = resolver.with_causality(input, named("input", input, options.input.has_value()), Causality::input);
  const std::string output = options.output.value_or(kDefaultFmuOutput);
  common.output =
      resolver.with_causality(output, named("output", output, options.output.has_value()), Causality::output);
  if (options.velocity) {
    common.velocity = resolver.with_causality(*options.velocity, named("velocity", *options.velocity, true),
                                              Causality::output);
  }
  // Without an option, x0 and v0 when the FMU has them (fmu_axis_plant.hpp: what reset() does
  // without them).
  const auto start_variable = [&](const std::optional<std::string>& given, const char* key,
                                  const char* fallback) -> std::optional<RealVariable> {
    if (given) return resolver.start_variable(*given, named(key, *given, true));
    if (resolver.has(fallback)) return resolver.start_variable(fallback, named(key, fallback, false));
    return std::nullopt;
  };
  common.position_start = start_variable(options.position_start, "position_start", kDefaultFmuPositionStart);
  common.velocity_start = start_variable(options.velocity_start, "velocity_start", kDefaultFmuVelocityStart);
  // FMI 2.0, 2.2.5: the DefaultExperiment's stepSize is the step the model was made for.
  common.step_s = options.step_s.value_or(description.default_step_size_s.value_or(1e-3));
  common.fixed_step = !description.co_simulation.can_handle_variable_communication_step_size;

  const std::vector<ResolvedParameter> parameters = resolve_parameters(options, resolver, axis_count);
  AxisSet set;
  for (std::size_t axis = 0; axis < axis_count; ++axis) {
    auto setup = std::make_shared<FmuAxisSetup>(common);
    setup->axis = axis;
    for (const ResolvedParameter& p : parameters) {
      if (!p.axis || *p.axis == axis) setup->parameters.emplace_back(p.variable, p.value);
    }
    if (axis < overrides.size()) {
      for (const auto& [key, value] : overrides[axis].parameters) {
        setup->parameters.emplace_back(
            resolver.parameter(key, "axis " + std::to_string(axis) + " parameter '" + key + "'"), value);
      }
    }
    set.axes.push_back(std::make_unique<FmuAxisPlant>(std::move(setup)));
  }
  std::ostringstream out;
  out << "fmu:" << printable_text(common.options_text) << " (model " << quoted(description.model_name) << ", FMI "
      << printable_text(description.fmi_version) << " co-simulation, " << axis_count
      << (axis_count == 1 ? " axis)" : " axes)");
  set.description = out.str();
  return set;
}

FmuPlantSummary summarize_fmu_plant(std::string_view text) {
  const FmuPlantOptions options = parse_fmu_plant_options(text);
  const ModelDescription description = FmuModel::read_description(options.path);
  FmuPlantSummary out;
  out.model_name = printable_text(description.model_name);
  if (const ScalarVariable* input = description.find(options.input.value_or(kDefaultFmuInput))) {
    out.input_unit = input->unit;
  }
  for (const ScalarVariable& v : description.variables) {
    if (v.type != VariableType::real || v.causality != Causality::parameter) continue;
    std::ostringstream line;
    line << "FMU parameter";
    if (!v.unit.empty()) line << " (" << v.unit << ")";
    if (v.start) line << "; " << *v.start;
    out.parameters.push_back({printable_text(v.name, kMaxVariableNameLength), line.str()});
  }
  return out;
}

}  // namespace netmc::plant::fmu
