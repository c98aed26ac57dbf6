// Paper 004's PID-type cross-coupling with a low-pass (eq. 13, Table 3), discretized by Tustin.
#include "control/cross_coupling/tustin_cross_coupling.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {

void register_low_pass_pid_cross_coupling(ControllerRegistry& registry) {
  registry.add(GainGroup{"lpccc", "--lpccc", "Paper 004's low-pass PID cross-coupling (eq. 13)", false,
                         {{"kp", "proportional gain", "5e5"},
                          {"ki", "integral gain", "1e8"},
                          {"kd", "derivative gain", "3"},
                          {"low_pass_hz", "low-pass frequency (Hz)", "100", GainKey::Kind::number, GainCheck::positive},
                          {"low_pass_damping", "low-pass damping ratio", "0.707", GainKey::Kind::number,
                           GainCheck::positive}}});
  ControllerFamily family;
  family.names = {"lpccc"};
  family.role = ControllerRole::compensator;
  family.summary = "PID-type cross-coupling with a low-pass, Tustin-discretized";
  family.source = "paper 004, eq. 13, Table 3";
  family.gain_groups = {"lpccc"};
  family.plants = {"stage004"};
  family.make_compensator = [](const ControllerContext& context) -> std::unique_ptr<control::ContourCompensator> {
    control::FilteredPidCrossCouplingGains gains;
    const auto& g = context.gains;
    g.read("lpccc", "kp", gains.kp);
    g.read("lpccc", "ki", gains.ki);
    g.read("lpccc", "kd", gains.kd);
    g.read("lpccc", "low_pass_hz", gains.low_pass_hz);
    g.read("lpccc", "low_pass_damping", gains.low_pass_damping);
    return std::make_unique<control::TustinCrossCoupling>(
        control::make_low_pass_pid_cross_coupling(gains, context.sample_period_s));
  };
  registry.add(std::move(family));
}

}  // namespace netmc::job
