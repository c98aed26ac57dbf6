// ADRC in the global task coordinate frame (gtcf-adrc): a PD per task coordinate over an
// extended state observer each, on the thesis's nominal Cartesian model.
#include <stdexcept>

#include "control/group/planar_contour_group.hpp"
#include "control/task_space/task_space_adrc.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {

void register_task_space_adrc(ControllerRegistry& registry) {
  const auto bandwidth = [](const char* name, const char* meaning, const char* default_text) {
    GainKey key{name, meaning, default_text, GainKey::Kind::number, GainCheck::positive};
    if (std::string_view(name) == "woc" || std::string_view(name) == "wom") key.flag_aliases = {name, "wo"};
    return key;
  };
  GainKey delay{"observer_input_delay", "periods the observers see the task command late", "0", GainKey::Kind::number,
                GainCheck::whole};
  delay.flag_aliases = {"delay"};
  registry.add(GainGroup{"gtcf_adrc", "--gtcf-adrc", "Task-space ADRC bandwidths (rad/s)", false,
                         {bandwidth("wc", "contour loop bandwidth (rad/s)", "300"),
                          bandwidth("wm", "tangential loop bandwidth (rad/s)", "100"),
                          bandwidth("woc", "contour observer bandwidth (rad/s); wo= sets both observers", "1500"),
                          bandwidth("wom", "tangential observer bandwidth (rad/s)", "500"),
                          {"observer", "observer discretization", "euler", GainKey::Kind::choice, GainCheck::finite,
                           {"euler", "zoh"}},
                          delay}});
  ControllerFamily family;
  family.names = {"gtcf-adrc"};
  family.role = ControllerRole::group;
  family.summary = "ADRC per task coordinate in the global frame (ESO and PD on the contour and tangential errors)";
  family.source = "paper 001's ADRC in the thesis's GTCF";
  family.gain_groups = {"gtcf_adrc"};
  family.plants = {"linmotor"};
  family.make_group = [](const ControllerContext& context, std::string_view name,
                         std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    const auto* trajectory = std::get_if<std::shared_ptr<const control::ReferenceTrajectory>>(&context.reference);
    if (!trajectory) throw std::invalid_argument("controller: " + std::string(name) + " runs two-axis contours only");
    control::GtcfAdrcGains gains;
    const auto& g = context.gains;
    g.read("gtcf_adrc", "wc", gains.loop_bandwidth[0]);
    g.read("gtcf_adrc", "wm", gains.loop_bandwidth[1]);
    g.read("gtcf_adrc", "woc", gains.observer_bandwidth[0]);
    g.read("gtcf_adrc", "wom", gains.observer_bandwidth[1]);
    if (const auto observer = g.choice("gtcf_adrc", "observer")) {
      gains.discretization =
          *observer == "zoh" ? control::Discretization::zero_order_hold : control::Discretization::forward_euler;
    }
    double periods = 0.0;
    if (g.read("gtcf_adrc", "observer_input_delay", periods)) {
      if (periods > 100000) {
        throw std::invalid_argument(g.field("gtcf_adrc", "observer_input_delay") + ": expected at most 100000 periods");
      }
      gains.observer_input_delay = static_cast<unsigned>(periods);
    }
    return std::make_unique<control::PlanarGroupController>(std::make_unique<control::TaskSpaceAdrc>(
        gains, context.sample_period_s, control::make_task_frame(**trajectory)));
  };
  registry.add(std::move(family));
}

}  // namespace netmc::job
