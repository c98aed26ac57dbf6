// Paper 004's QFT-designed cross-coupling controller (eq. 20), discretized by Tustin.
#include "control/cross_coupling/tustin_cross_coupling.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {

void register_qft_cross_coupling(ControllerRegistry& registry) {
  ControllerFamily family;
  family.names = {"qftccc"};
  family.role = ControllerRole::compensator;
  family.summary = "QFT-designed cross-coupling controller, Tustin-discretized";
  family.source = "paper 004, eq. 20";
  family.plants = {"stage004"};
  family.make_compensator = [](const ControllerContext& context) -> std::unique_ptr<control::ContourCompensator> {
    return std::make_unique<control::TustinCrossCoupling>(control::make_qft_cross_coupling(context.sample_period_s));
  };
  registry.add(std::move(family));
}

}  // namespace netmc::job
