// PID cross-coupling (paper 001, eq. 14 with PID on the estimated contour error): the contour
// compensator that adds U_e along the coupling direction.
#include "control/cross_coupling/pid_cross_coupling.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {

void register_pid_cross_coupling(ControllerRegistry& registry) {
  registry.add(GainGroup{"pidccc", "--pidccc", "PID cross-coupling gains", false,
                         {{"kp", "per m of contour error", "500"}, {"ki", "per m*s", "0"}, {"kd", "per m/s", "50"}}});
  ControllerFamily family;
  family.names = {"pidccc"};
  family.role = ControllerRole::compensator;
  family.summary = "PID on the estimated contour error, along the coupling direction";
  family.source = "paper 001";
  family.gain_groups = {"pidccc"};
  family.plants = {"seed001"};
  family.make_compensator = [](const ControllerContext& context) -> std::unique_ptr<control::ContourCompensator> {
    control::PidCrossCouplingGains gains;
    context.gains.read("pidccc", "kp", gains.kp);
    context.gains.read("pidccc", "ki", gains.ki);
    context.gains.read("pidccc", "kd", gains.kd);
    return std::make_unique<control::PidCrossCoupling>(gains, context.sample_period_s);
  };
  registry.add(std::move(family));
}

}  // namespace netmc::job
