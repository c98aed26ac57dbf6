// The thesis's task-space contouring laws (paper 000, chapters 2-4) in the global task coordinate
// frame (gtcf-*) or the local one (ltcf-*): SARC (ch. 2), DARC and DIARC (ch. 3), DARC with
// cogging compensation (ch. 4), and GTCF-SARC on a circle in space (ch. 6). They share one group of
// settings, task_space: the initialization filter, Lambda and K per task coordinate, the local
// frame's rate and the cogging adaptation.
#include <fmt/format.h>

#include <stdexcept>

#include "control/group/planar_contour_group.hpp"
#include "control/group/spatial_contour_group.hpp"
#include "control/task_space/task_space_cogging_darc.hpp"
#include "control/task_space/task_space_darc.hpp"
#include "control/task_space/task_space_diarc.hpp"
#include "control/task_space/task_space_sarc.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {
namespace {

// What the task_space group sets, over a law's own defaults.
struct TaskSpaceSettings {
  std::optional<double> lambda_c, lambda_m, k_c, k_m, cogging_adaptation;
  control::InitializationFilterSettings filter;
  control::LocalFrameRate local_rate = control::LocalFrameRate::frozen;

  template <class Gains>
  void apply(Gains& gains) const {
    if (lambda_c) gains.lambda[0] = *lambda_c;
    if (lambda_m) gains.lambda[1] = *lambda_m;
    if (k_c) gains.feedback[0] = *k_c;
    if (k_m) gains.feedback[1] = *k_m;
  }
};

TaskSpaceSettings read_settings(const GainsReader& g) {
  TaskSpaceSettings s;
  double value = 0.0;
  if (g.read("task_space", "lambda_c", value)) s.lambda_c = value;
  if (g.read("task_space", "lambda_m", value)) s.lambda_m = value;
  if (g.read("task_space", "k_c", value)) s.k_c = value;
  if (g.read("task_space", "k_m", value)) s.k_m = value;
  if (g.read("task_space", "cogging_adaptation", value)) {
    if (value > 1e6) {
      throw std::invalid_argument(g.field("task_space", "cogging_adaptation") + ": expected a number in [0, 1e6]");
    }
    s.cogging_adaptation = value;
  }
  s.filter.enabled = g.choice("task_space", "initialization_filter") == "on";
  g.read("task_space", "filter_wc", s.filter.contour_bandwidth);
  g.read("task_space", "filter_wm", s.filter.tangential_bandwidth);
  if (g.choice("task_space", "ltcf_rotation") == "on") s.local_rate = control::LocalFrameRate::rotating;
  return s;
}

const control::ReferenceTrajectory& planar(const ControllerContext& context, std::string_view name) {
  const auto* trajectory = std::get_if<std::shared_ptr<const control::ReferenceTrajectory>>(&context.reference);
  if (!trajectory) throw std::invalid_argument("controller: " + std::string(name) + " runs two-axis contours only");
  return **trajectory;
}

// The local frame's rate for ltcf-NAME (the global frame has none).
control::LocalFrameRate rate_of(std::string_view name, const TaskSpaceSettings& s) {
  return name.starts_with("ltcf-") ? s.local_rate : control::LocalFrameRate::frozen;
}

// gtcf-NAME in the contour's global frame, ltcf-NAME in the local one (frame null).
std::shared_ptr<const control::TaskFrame> frame_of(std::string_view name, const control::ReferenceTrajectory& trajectory) {
  return name.starts_with("gtcf-") ? control::make_task_frame(trajectory) : nullptr;
}

std::unique_ptr<control::GroupController> planar_group(std::unique_ptr<control::ContourController> controller) {
  return std::make_unique<control::PlanarGroupController>(std::move(controller));
}

ControllerFamily task_space_family(std::vector<std::string> names, std::string summary, std::string source) {
  ControllerFamily family;
  family.names = std::move(names);
  family.role = ControllerRole::group;
  family.summary = std::move(summary);
  family.source = std::move(source);
  family.gain_groups = {"task_space"};
  family.plants = {"linmotor", "linmotor-flex"};
  return family;
}

}  // namespace

void register_task_space(ControllerRegistry& registry) {
  const auto rate = [](const char* name, const char* meaning, const char* default_text, const char* alias = nullptr) {
    GainKey key{name, meaning, default_text, GainKey::Kind::number, GainCheck::positive};
    if (alias) key.flag_aliases = {alias};
    return key;
  };
  GainKey filter{"initialization_filter", "the initialization filter of eq. 2-67 (gtcf-* only)", "off",
                 GainKey::Kind::choice, GainCheck::finite, {"off", "on"}};
  filter.flag_aliases = {"init_filter"};
  GainKey rotation{"ltcf_rotation", "ltcf-*: differentiate T(alpha) too (e' = T (q' - q_d') + T' e)", "off",
                   GainKey::Kind::choice, GainCheck::finite, {"off", "on"}};
  GainKey cogging{"cogging_adaptation",
                  "*-darc-cogging: adaptation of the 12 cogging harmonics (thesis ch. 4; 0: none, C1)", "500",
                  GainKey::Kind::number, GainCheck::non_negative};
  cogging.flag_aliases = {"cogging"};
  registry.add(GainGroup{"task_space", "--task-space", "Task-space controllers (gtcf-*, ltcf-*)", false,
                         {filter, rate("filter_wc", "initialization filter's contour bandwidth (rad/s)", "8", "wc"),
                          rate("filter_wm", "its tangential bandwidth (rad/s)", "1", "wm"),
                          rate("lambda_c", "Lambda, contour (1/s)", "100"),
                          rate("lambda_m", "Lambda, tangential (1/s)", "30"), rate("k_c", "K, contour (V/(m/s))", "100"),
                          rate("k_m", "K, tangential (V/(m/s))", "60"), rotation, cogging}});

  auto sarc = task_space_family({"gtcf-sarc", "ltcf-sarc"},
                                "sliding-mode adaptive robust control in the task frame; gtcf-sarc also on a "
                                "circle in space (three axes)",
                                "thesis, ch. 2 (ch. 6 in space)");
  sarc.make_group = [](const ControllerContext& context, std::string_view name,
                       std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    const TaskSpaceSettings s = read_settings(context.gains);
    if (const auto* circle = std::get_if<std::shared_ptr<const control::SpatialCircle>>(&context.reference)) {
      if (name != "gtcf-sarc") {
        throw std::invalid_argument("controller: a three-axis contour runs gtcf-sarc, got '" + std::string(name) + "'");
      }
      control::SpatialSarcGains gains;
      // Both contour coordinates take the contour gains.
      if (s.lambda_c) gains.lambda[0] = gains.lambda[1] = *s.lambda_c;
      if (s.lambda_m) gains.lambda[2] = *s.lambda_m;
      if (s.k_c) gains.feedback[0] = gains.feedback[1] = *s.k_c;
      if (s.k_m) gains.feedback[2] = *s.k_m;
      return std::make_unique<control::SpatialSarcGroupController>(gains, context.sample_period_s, *circle);
    }
    const auto& trajectory = planar(context, name);
    control::SarcGains gains;
    s.apply(gains);
    return planar_group(std::make_unique<control::TaskSpaceSarc>(gains, context.sample_period_s,
                                                                 frame_of(name, trajectory), s.filter, rate_of(name, s)));
  };
  registry.add(std::move(sarc));

  auto darc = task_space_family({"gtcf-darc", "ltcf-darc"},
                                "direct adaptive robust control in the task frame (projection adaptation)",
                                "thesis, ch. 3");
  darc.make_group = [](const ControllerContext& context, std::string_view name,
                       std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    const TaskSpaceSettings s = read_settings(context.gains);
    const auto& trajectory = planar(context, name);
    control::DarcGains gains;
    s.apply(gains);
    return planar_group(std::make_unique<control::TaskSpaceDarc>(gains, context.sample_period_s,
                                                                 frame_of(name, trajectory), s.filter, rate_of(name, s)));
  };
  registry.add(std::move(darc));

  auto diarc = task_space_family({"gtcf-diarc", "ltcf-diarc"},
                                 "DIARC in the task frame: least-squares adaptation of 8 parameters", "thesis, ch. 3");
  diarc.make_group = [](const ControllerContext& context, std::string_view name,
                        std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    const TaskSpaceSettings s = read_settings(context.gains);
    const auto& trajectory = planar(context, name);
    control::DiarcGains gains;
    s.apply(gains);
    return planar_group(std::make_unique<control::TaskSpaceDiarc>(gains, context.sample_period_s,
                                                                  frame_of(name, trajectory), s.filter, rate_of(name, s)));
  };
  registry.add(std::move(diarc));

  auto cogging_darc = task_space_family({"gtcf-darc-cogging", "ltcf-darc-cogging"},
                                        "DARC with adaptive compensation of the cogging force's harmonics",
                                        "thesis, ch. 4");
  cogging_darc.make_group = [](const ControllerContext& context, std::string_view name,
                               std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    const TaskSpaceSettings s = read_settings(context.gains);
    const auto& trajectory = planar(context, name);
    control::CoggingDarcGains gains;
    s.apply(gains);
    if (s.cogging_adaptation) {
      for (int row = 6; row < 6 + 4 * control::kCoggingHarmonicsPerAxis; ++row) {
        gains.adaptation[row] = *s.cogging_adaptation;
      }
    }
    return planar_group(std::make_unique<control::TaskSpaceCoggingDarc>(
        gains, context.sample_period_s, frame_of(name, trajectory), s.filter, rate_of(name, s)));
  };
  registry.add(std::move(cogging_darc));
}

}  // namespace netmc::job
