#include "server/job/delay_compensators.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <stdexcept>

#include "plant/nominal_axis_model.hpp"
#include "plant/plant_catalog.hpp"
#include "server/job/job_builder.hpp"
#include "server/job/quantity_text.hpp"

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
      {"predictor", "predictor[:playout=D|bound]",
       "each axis's state predicted from its newest time-stamped feedback over that feedback's age plus the "
       "setpoint's planned travel (the longest downlink delay the axes reported lately, and at least the playout "
       "delay D if given: bound is the upper bound of the job's own delay profile; an axis holds an earlier "
       "arrival until then), with the commands already sent; the controller (axis law and contour compensator "
       "alike) acts on the predicted positions and the reference at the instant its command will act",
       fmt::format("the plant's nominal model x'' = a x' + b u - c tanh(x'/v_s) + d where netmc knows it ({}), else "
                   "the axis law's own (ADRC's observer model x'' = b0 u + d); d estimated, held over the prediction",
                   fmt::join(plants_with_nominal_models(), ", ")),
       "Smith 1957; Yi, An and Choi 2017; the filtered Smith predictor (arXiv 2506.23421); playout: Luck and Ray "
       "1990"},
      {"packets", "packets[:horizon=N]",
       fmt::format("packetized predictive control: each setpoint carries the commands for its cycle and the next N-1 "
                   "(default {}, at most {}), computed by a copy of the controller run ahead on the positions the "
                   "model predicts with the commands before them; the axis plays, each period, the command meant for "
                   "it from the freshest setpoint it holds, so a lost or late setpoint is covered for up to N-1 "
                   "periods, then the last command is held. The first command acts at the cycle's own instant (no "
                   "delay planned)",
                   kDefaultHorizon, sim::DelayCompensation::kMaxHorizon),
       "as predictor (the laws that can be copied: contouring controllers of axis laws and compensators)",
       "Bemporad 1998; Quevedo and Nešić 2011; Beger, Lin, Stanojevic and Hirche (arXiv 2512.11492)"},
      {"predictor+packets", "predictor+packets[:horizon=N,playout=D|bound]",
       "both: the first command planned over the measured delay as predictor does (on a grid of whole periods), "
       "the next N-1 as packets computes them",
       "as predictor", "as predictor and packets"},
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

bool takes_horizon(std::string_view name) { return name == "packets" || name == "predictor+packets"; }

std::optional<netmc::v1::CompensationSpec> parse_compensation(std::string_view text, std::string_view flag) {
  const std::size_t colon = text.find(':');
  const std::string_view name = text.substr(0, colon);
  if (require_compensator(name, flag).name == "none" && colon == std::string_view::npos) return std::nullopt;
  netmc::v1::CompensationSpec spec;
  spec.set_name(std::string(name));
  if (colon == std::string_view::npos) return spec;
  const std::string_view options = text.substr(colon + 1);
  std::vector<std::string> allowed;
  if (takes_horizon(name)) allowed.push_back("horizon");
  if (takes_playout(name)) allowed.push_back("playout");
  if (allowed.empty()) {
    throw std::invalid_argument(fmt::format("{}: {} takes no options, got '{}'", flag, name, options.substr(0, 80)));
  }
  const auto keys = parse_keys(options, flag, allowed);
  if (const auto found = keys.find("horizon"); found != keys.end()) {
    const std::string_view value = found->second;
    unsigned horizon = 0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), horizon);
    if (value.empty() || error != std::errc{} || end != value.data() + value.size() || horizon < 2 ||
        horizon > sim::DelayCompensation::kMaxHorizon) {
      throw std::invalid_argument(fmt::format("{}: expected {}:horizon=N with N an integer of 2 to {}, got '{}'", flag,
                                              name, sim::DelayCompensation::kMaxHorizon, text.substr(0, 80)));
    }
    spec.set_horizon(horizon);
  }
  if (const auto found = keys.find("playout"); found != keys.end()) {
    if (found->second == "bound") {
      spec.set_playout_at_delay_bound(true);
    } else {
      const double playout_s = parse_quantity(found->second, Quantity::time, fmt::format("{} playout", flag));
      if (!(playout_s > 0.0 && playout_s <= sim::DelayCompensation::kMaxPlayoutS)) {
        throw std::invalid_argument(fmt::format("{}: expected {}:playout=DURATION (above 0, at most {} s) or "
                                                "playout=bound, got '{}'",
                                                flag, name, sim::DelayCompensation::kMaxPlayoutS, found->second.substr(0, 80)));
      }
      spec.set_playout_s(playout_s);
    }
  }
  return spec;
}

bool takes_playout(std::string_view name) { return name == "predictor" || name == "predictor+packets"; }

std::string compensation_text(const netmc::v1::CompensationSpec& spec) {
  std::vector<std::string> options;
  if (spec.horizon() != 0) options.push_back(fmt::format("horizon={}", spec.horizon()));
  if (spec.playout_at_delay_bound()) {
    options.push_back("playout=bound");
  } else if (spec.playout_s() != 0.0) {
    options.push_back(fmt::format("playout={}s", spec.playout_s()));
  }
  return options.empty() ? spec.name() : fmt::format("{}:{}", spec.name(), fmt::join(options, ","));
}

std::optional<sim::DelayCompensation> build_compensation(const netmc::v1::JobSpec& spec,
                                                         const sim::JobReference& reference,
                                                         const std::vector<std::string>& axis_names) {
  if (!spec.has_compensation()) return std::nullopt;
  const std::string& name = spec.compensation().name();
  if (require_compensator(name, "compensation.name").name == "none") return std::nullopt;
  sim::DelayCompensation compensation;
  if (takes_horizon(name)) {
    const std::uint32_t horizon = spec.compensation().horizon() == 0 ? kDefaultHorizon : spec.compensation().horizon();
    if (horizon < 2 || horizon > sim::DelayCompensation::kMaxHorizon) {
      throw std::invalid_argument(fmt::format("compensation.horizon: expected 2 to {} commands, got {}",
                                              sim::DelayCompensation::kMaxHorizon, horizon));
    }
    compensation.horizon = horizon;
    compensation.predict_delay = name != "packets";
  } else if (spec.compensation().horizon() != 0) {
    throw std::invalid_argument(fmt::format("compensation.horizon: {} takes none (packets and predictor+packets do), got {}",
                                            name, spec.compensation().horizon()));
  }
  const auto& playout = spec.compensation();
  if (playout.playout_at_delay_bound() || playout.playout_s() != 0.0) {
    if (!takes_playout(name)) {
      throw std::invalid_argument(fmt::format(
          "compensation.playout_s: {} plans no delay (predictor and predictor+packets do)", name));
    }
    if (playout.playout_at_delay_bound()) {
      const auto bound = delay_profile_bound_s(spec.downlink().delay());
      if (!bound) {
        throw std::invalid_argument(
            "compensation.playout_at_delay_bound: the downlink delay has no upper bound netmc knows (a trace, an "
            "untruncated normal or pareto delay); give playout=DURATION");
      }
      compensation.playout_s = *bound;
    } else if (!(playout.playout_s() > 0.0 && playout.playout_s() <= sim::DelayCompensation::kMaxPlayoutS)) {
      throw std::invalid_argument(fmt::format("compensation.playout_s: expected above 0 and at most {} s, got {}",
                                              sim::DelayCompensation::kMaxPlayoutS, playout.playout_s()));
    } else {
      compensation.playout_s = playout.playout_s();
    }
  }
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
