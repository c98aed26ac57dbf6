// PD-type iterative learning cross-coupling (paper 001, eq. 14), with the optional Q-filter and
// lead of its stable form: the compensation of iteration j learned from the contour error of j-1.
#include <cstddef>

#include "control/cross_coupling/iterative_learning_cross_coupling.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {

void register_iterative_learning(ControllerRegistry& registry) {
  registry.add(GainGroup{
      "ilccc", "--ilc", "ILC cross-coupling gains", false,
      {{"kcp", "learning gain on the contour error", "40"},
       {"kcd", "learning gain on its rate", "40"},
       {"forgetting", "forgetting factor in [0, 1)", "0", GainKey::Kind::number, GainCheck::non_negative},
       {"q_cutoff_hz", "Q-filter cutoff (Hz); 0: none", "0", GainKey::Kind::number, GainCheck::non_negative, {}, 0,
        {"q"}},
       {"lead_samples", "learn from eps(k + lead)", "0", GainKey::Kind::number, GainCheck::whole, {}, 0, {"lead"}}}});
  ControllerFamily family;
  family.names = {"ilccc"};
  family.role = ControllerRole::compensator;
  family.summary = "PD-type iterative learning of the coupling command from the last iteration's contour error";
  family.source = "paper 001, eq. 14";
  family.gain_groups = {"ilccc"};
  family.plants = {"seed001"};
  family.make_compensator = [](const ControllerContext& context) -> std::unique_ptr<control::ContourCompensator> {
    control::IterativeLearningGains gains;
    const auto& g = context.gains;
    g.read("ilccc", "kcp", gains.kcp);
    g.read("ilccc", "kcd", gains.kcd);
    g.read("ilccc", "forgetting", gains.forgetting);
    g.read("ilccc", "q_cutoff_hz", gains.q_cutoff_hz);
    double lead = 0.0;
    if (g.read("ilccc", "lead_samples", lead)) gains.lead_samples = static_cast<std::size_t>(lead);
    return std::make_unique<control::IterativeLearningCrossCoupling>(gains, context.sample_period_s);
  };
  registry.add(std::move(family));
}

}  // namespace netmc::job
