// PID, per axis: u = kp e + ki integral of e + kd de/dt on the position error.
//
// The defaults place a triple pole at 60 rad/s on seed001's X axis (paper 001, eq. 3: x'' =
// -20 x' + 20 u): s^3 + 20 (1 + kd) s^2 + 20 kp s + 20 ki = (s + 60)^3 gives kd = 8, kp = 540,
// ki = 10800. Its Y axis (b = 10) is stable with the same gains (Routh: 90 * 5400 > 108000).
// Other plants take gains of their own (--pid).
#include "control/axis/pid_axis_controller.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {

void register_pid(ControllerRegistry& registry) {
  registry.add(GainGroup{"pid", "--pid", "Per-axis PID gains", true,
                         {{"kp", "per m of position error", "540"},
                          {"ki", "per m*s", "10800"},
                          {"kd", "per m/s (backward difference of the error)", "8"}}});
  ControllerFamily family;
  family.names = {"pid"};
  family.role = ControllerRole::axis;
  family.summary = "PID per axis on the position error";
  family.source = "textbook; defaults: a triple pole at 60 rad/s on seed001's X axis";
  family.gain_groups = {"pid"};
  family.plants = {"seed001"};
  family.make_axis = [](const ControllerContext& context, std::size_t axis) -> std::unique_ptr<control::AxisController> {
    control::PidAxisGains gains{540.0, 10800.0, 8.0};
    context.gains.read("pid", "kp", axis, gains.kp);
    context.gains.read("pid", "ki", axis, gains.ki);
    context.gains.read("pid", "kd", axis, gains.kd);
    return std::make_unique<control::PidAxisController>(gains, context.sample_period_s);
  };
  registry.add(std::move(family));
}

}  // namespace netmc::job
