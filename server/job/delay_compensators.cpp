#include "server/job/delay_compensators.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>

#include "plant/nominal_axis_model.hpp"
#include "plant/plant_catalog.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::job {
namespace {

// The catalog's plants that have a nominal model (plant::nominal_axis_model).
std::vector<std::string> plants_with_nominal_models() {
  std::vector<std::string> names;
  for (const auto& name : plant::plant_names()) {
    if (plant::nominal_axis_model(name, 0)) names.push_back(name);
  }
  return names;
}

}  // namespace

const std::vector<DelayCompensatorDescriptor>& delay_compensators() {
  static const std::vector<DelayCompensatorDescriptor> compensators = {
      {"none", "none", "no compensation: the controller sees the newest feedback and the reference at t_k", "-",
       "paper 001 (the papers' loop)"},
      {"predictor", "predictor",
       "each axis's state predicted from its newest time-stamped feedback over that feedback's age plus the "
       "setpoint's planned travel (the longest downlink delay the axes reported lately; an axis holds an earlier "
       "arrival until then), with the commands already sent; the controller (axis law and contour compensator "
       "alike) acts on the predicted positions and the reference at the instant its command will act",
       fmt::format("the plant's nominal model x'' = a x' + b u - c tanh(x'/v_s) + d where netmc knows it ({}), else "
                   "the axis law's own (ADRC's observer model x'' = b0 u + d); d estimated, held over the prediction",
                   fmt::join(plants_with_nominal_models(), ", ")),
       "Smith 1957; Yi, An and Choi 2017; the filtered Smith predictor (arXiv 2506.23421)"},
  };
  return compensators;
}

std::string delay_compensator_syntax() {
  std::string text;
  for (const auto& compensator : delay_compensators()) text += (text.empty() ? "" : " | ") + compensator.syntax;
  return text;
}

std::string delay_compensators_markdown_table() {
  std::string table =
      "| compensator | what it does | predicts with | source |\n"
      "| --- | --- | --- | --- |\n";
  for (const auto& c : delay_compensators()) {
    table += fmt::format("| `{}` | {} | {} | {} |\n", c.syntax, c.summary, c.model, c.source);
  }
  return table;
}

namespace {

// The descriptor named `name`; std::invalid_argument naming `field` (the flag or the spec field).
const DelayCompensatorDescriptor& require_compensator(std::string_view name, std::string_view field) {
  for (const auto& compensator : delay_compensators()) {
    if (compensator.name == name) return compensator;
  }
  throw std::invalid_argument(fmt::format("{}: expected {}, got '{}'", field, delay_compensator_syntax(), name.substr(0, 80)));
}

}  // namespace

std::optional<netmc::v1::CompensationSpec> parse_compensation(std::string_view text, std::string_view flag) {
  if (require_compensator(text, flag).name == "none") return std::nullopt;
  netmc::v1::CompensationSpec spec;
  spec.set_name(std::string(text));
  return spec;
}

std::optional<sim::DelayCompensation> build_compensation(const netmc::v1::JobSpec& spec,
                                                         const sim::JobReference& reference,
                                                         const std::vector<std::string>& axis_names) {
  if (!spec.has_compensation()) return std::nullopt;
  const std::string& name = spec.compensation().name();
  if (require_compensator(name, "compensation.name").name == "none") return std::nullopt;
  sim::DelayCompensation compensation;
  const auto& registry = ControllerRegistry::global();
  const auto law_models = registry.prediction_models(spec.controller(), reference, axis_names, spec.sample_period_s());
  for (std::size_t axis = 0; axis < axis_names.size(); ++axis) {
    // The plant's nominal model where netmc knows one; its observer as fast as the law's own.
    if (const auto nominal = plant::nominal_axis_model(spec.plant(), plant_axis_index(axis_names, axis))) {
      control::PredictionModel model;
      model.damping_per_s = nominal->damping_per_s;
      model.input_gain = nominal->input_gain;
      model.coulomb_m_s2 = nominal->coulomb_m_s2;
      model.coulomb_velocity_scale_m_s = nominal->coulomb_velocity_scale_m_s;
      if (law_models) model.observer_bandwidth_rad_s = (*law_models)[axis].observer_bandwidth_rad_s;
      compensation.axis_models.push_back(model);
    } else if (law_models) {
      compensation.axis_models.push_back((*law_models)[axis]);
    } else {
      throw std::invalid_argument(fmt::format(
          "compensation: {} needs a model of each axis: plant '{}' has no nominal model netmc knows ({} have) and "
          "controller '{}' has none of its own (laws that have: {})",
          name, spec.plant().substr(0, 80), fmt::join(plants_with_nominal_models(), ", "),
          spec.controller().name().substr(0, 80), fmt::join(registry.predicting_laws(), ", ")));
    }
  }
  return compensation;
}

}  // namespace netmc::job
