// The thesis's single-axis tracking laws for a drive behind a dead zone (chapter 5): DIARC with
// the dead zone ignored (C1, axis-diarc), a nominal (C2) or the exact (C4) fixed inverse, with
// the dead zone estimated (C3, axis-diarc-dead-zone), and the adaptive variable-structure law
// (C5, axis-avsc). Defaults: the thesis's gains, which fit the hiwin stage.
#include <cmath>
#include <stdexcept>

#include "control/dead_zone/adaptive_variable_structure_controller.hpp"
#include "control/dead_zone/dead_zone_diarc.hpp"
#include "control/dead_zone/fixed_inverse_diarc.hpp"
#include "control/group/single_axis_group.hpp"
#include "server/job/controller_registry.hpp"
#include "server/job/dead_zone_spec.hpp"

namespace netmc::job {
namespace {

control::DiarcLoopGains read_loop(const GainsReader& g) {
  control::DiarcLoopGains loop;
  g.read("axis_diarc", "lambda", loop.lambda);
  g.read("axis_diarc", "feedback", loop.feedback);
  g.read("axis_diarc", "disturbance_adaptation", loop.disturbance_adaptation);
  g.read("axis_diarc", "disturbance_bound", loop.disturbance_bound);
  return loop;
}

// Theta = [B, A, m_r, m_r b_r, m_l, m_l b_l] of axis-diarc-dead-zone, six numbers.
void read_theta(const GainsReader& g, const char* key, control::DeadZoneTheta& target) {
  const auto values = g.list("axis_diarc", key);
  if (!values) return;
  for (int i = 0; i < 6; ++i) {
    if (std::abs((*values)[static_cast<std::size_t>(i)]) > 1e6) {
      throw std::invalid_argument(g.field("axis_diarc", key) + ": expected finite numbers within +-1e6");
    }
    target[i] = (*values)[static_cast<std::size_t>(i)];
  }
}

std::unique_ptr<control::GroupController> tracking_group(std::unique_ptr<control::TrackingController> controller) {
  return std::make_unique<control::TrackingGroupController>(std::move(controller));
}

}  // namespace

void register_dead_zone_tracking(ControllerRegistry& registry) {
  const auto positive = [](const char* name, const char* meaning, const char* default_text) {
    return GainKey{name, meaning, default_text, GainKey::Kind::number, GainCheck::positive};
  };
  const auto theta = [](const char* name, const char* meaning) {
    return GainKey{name, meaning, "thesis", GainKey::Kind::list, GainCheck::finite, {}, 6};
  };
  registry.add(GainGroup{
      "axis_diarc", "--axis-diarc", "The thesis's single-axis DIARC loop (5-22) of axis-diarc*", false,
      {positive("lambda", "lambda (1/s): s = x~' + lambda x~", "200"),
       positive("feedback", "k_s (1/s)", "200"),
       positive("disturbance_adaptation", "gamma (1/s^2)", "1000"),
       positive("disturbance_bound", "d_cM (m/s^2)", "2"),
       GainKey{"right_break_v", "axis-diarc+exact-inverse: the dead zone's b_r >= 0 (V)", "1.2",
               GainKey::Kind::number, GainCheck::non_negative},
       GainKey{"left_break_v", "its b_l <= 0 (V)", "-1"},
       positive("right_slope", "its m_r", "0.9"),
       positive("left_slope", "its m_l", "1"),
       theta("initial_estimate", "axis-diarc-dead-zone: theta_hat(0) = [B, A, m_r, m_r b_r, m_l, m_l b_l]"),
       theta("lower", "its box's lower corner (5-53)"),
       theta("upper", "its box's upper corner (5-53)")}});
  registry.add(GainGroup{"avsc", "--avsc", "The thesis's adaptive variable-structure law (5-55)", false,
                         {positive("c1", "c1 (1/s)", "100"), positive("c2", "c2 (1/s)", "50"),
                          positive("mu", "mu", "1000"), positive("gamma", "Gamma", "10"),
                          positive("beta", "beta", "10")}});

  ControllerFamily diarc;
  diarc.names = {"axis-diarc", "axis-diarc+nominal-inverse", "axis-diarc+exact-inverse"};
  diarc.role = ControllerRole::tracking;
  diarc.summary = "DIARC on one axis: the dead zone ignored (C1), a nominal (C2) or the exact (C4) fixed inverse";
  diarc.source = "thesis, ch. 5 (5-22)";
  diarc.gain_groups = {"axis_diarc"};
  diarc.plants = {"hiwin"};
  diarc.make_group = [](const ControllerContext& context, std::string_view name,
                        std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    const auto handling = name == "axis-diarc"                   ? control::DeadZoneHandling::ignored
                          : name == "axis-diarc+nominal-inverse" ? control::DeadZoneHandling::nominal_inverse
                                                                 : control::DeadZoneHandling::exact_inverse;
    auto gains = control::FixedInverseDiarcGains::thesis(handling);
    gains.loop = read_loop(context.gains);
    if (handling == control::DeadZoneHandling::exact_inverse) {
      const auto& g = context.gains;
      netmc::v1::DeadZoneSpec exact;
      double value = 0.0;
      bool given = false;
      if (g.read("axis_diarc", "right_break_v", value)) given = true, exact.set_right_break_v(value);
      if (g.read("axis_diarc", "left_break_v", value)) given = true, exact.set_left_break_v(value);
      if (g.read("axis_diarc", "right_slope", value)) given = true, exact.set_right_slope(value);
      if (g.read("axis_diarc", "left_slope", value)) given = true, exact.set_left_slope(value);
      if (given) gains.inverse = build_dead_zone(exact, "controller.gains.axis_diarc");
    }
    return tracking_group(std::make_unique<control::FixedInverseDiarc>(gains, context.sample_period_s));
  };
  registry.add(std::move(diarc));

  ControllerFamily estimated;
  estimated.names = {"axis-diarc-dead-zone"};
  estimated.role = ControllerRole::tracking;
  estimated.summary = "DIARC with the dead zone estimated online (gated least squares) and inverted (C3)";
  estimated.source = "thesis, ch. 5 (5-22..5-42)";
  estimated.gain_groups = {"axis_diarc"};
  estimated.plants = {"hiwin"};
  estimated.make_group = [](const ControllerContext& context, std::string_view,
                            std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    control::DeadZoneDiarcGains gains;
    gains.loop = read_loop(context.gains);
    read_theta(context.gains, "initial_estimate", gains.initial_estimate);
    read_theta(context.gains, "lower", gains.lower);
    read_theta(context.gains, "upper", gains.upper);
    if (context.gains.list("axis_diarc", "lower") || context.gains.list("axis_diarc", "upper")) {
      // Lemma 5.2: beyond H = the widest spread of m_r b_r or m_l b_l over the box, the demand is
      // outside the gap whatever the estimates (the thesis's H = 2 is this for its box 5-53).
      gains.validate();
      gains.estimation_threshold = std::max(gains.upper[3] - gains.lower[3], gains.upper[5] - gains.lower[5]);
    }
    return tracking_group(std::make_unique<control::DeadZoneDiarc>(gains, context.sample_period_s));
  };
  registry.add(std::move(estimated));

  ControllerFamily avsc;
  avsc.names = {"axis-avsc"};
  avsc.role = ControllerRole::tracking;
  avsc.summary = "adaptive variable-structure control of a drive behind a dead zone (C5)";
  avsc.source = "thesis, ch. 5 (5-55)";
  avsc.gain_groups = {"avsc"};
  avsc.plants = {"hiwin"};
  avsc.make_group = [](const ControllerContext& context, std::string_view,
                       std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    control::AdaptiveVariableStructureGains gains;
    const auto& g = context.gains;
    g.read("avsc", "c1", gains.c1);
    g.read("avsc", "c2", gains.c2);
    g.read("avsc", "mu", gains.mu);
    g.read("avsc", "gamma", gains.parameter_adaptation);
    g.read("avsc", "beta", gains.beta);
    return tracking_group(std::make_unique<control::AdaptiveVariableStructureController>(gains, context.sample_period_s));
  };
  registry.add(std::move(avsc));
}

}  // namespace netmc::job
