// ADRC, per axis (paper 001, eqs. 5-9): tracking differentiator, third-order extended state
// observer, PD on the state error, disturbance rejection. Defaults: paper 001's gains.
#include "control/axis/adrc_controller.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {
namespace {

control::AdrcGains read_adrc_gains(const GainsReader& g, std::size_t axis) {
  control::AdrcGains gains;
  g.read("adrc", "r0", axis, gains.td_speed_factor);
  g.read("adrc", "w0", axis, gains.observer_bandwidth);
  g.read("adrc", "b0", axis, gains.input_gain);
  g.read("adrc", "kp", axis, gains.kp);
  g.read("adrc", "kd", axis, gains.kd);
  if (const auto observer = g.choice("adrc", "observer", axis)) {
    gains.observer_discretization =
        *observer == "zoh" ? control::Discretization::zero_order_hold : control::Discretization::forward_euler;
  }
  if (const auto input = g.choice("adrc", "observer_input", axis)) gains.observer_sees_sent_command = *input == "sent";
  return gains;
}

}  // namespace

void register_adrc(ControllerRegistry& registry) {
  registry.add(GainGroup{
      "adrc", "--adrc", "ADRC gains", true,
      {{"r0", "tracking differentiator speed factor (1/s)", "160", GainKey::Kind::number, GainCheck::positive},
       {"w0", "observer bandwidth (rad/s)", "100", GainKey::Kind::number, GainCheck::positive},
       {"b0", "input gain estimate (m/s^2 per input unit)", "20", GainKey::Kind::number, GainCheck::finite},
       {"kp", "gain on the position error", "0.08"},
       {"kd", "gain on the velocity error", "6"},
       {"observer", "observer discretization: euler (paper 001, eq. 9) or zoh (exact)", "euler",
        GainKey::Kind::choice, GainCheck::finite, {"euler", "zoh"}},
       {"observer_input", "what the observer is driven by: its own command or the one sent (with coupling)", "own",
        GainKey::Kind::choice, GainCheck::finite, {"own", "sent"}}}});
  ControllerFamily family;
  family.names = {"adrc"};
  family.role = ControllerRole::axis;
  family.summary = "ADRC per axis: tracking differentiator, third-order ESO, PD state-error feedback";
  family.source = "paper 001, eqs. 5-9";
  family.gain_groups = {"adrc"};
  family.plants = {"seed001"};
  family.make_axis = [](const ControllerContext& context, std::size_t axis) -> std::unique_ptr<control::AxisController> {
    return std::make_unique<control::AdrcController>(read_adrc_gains(context.gains, axis), context.sample_period_s);
  };
  // Its observer's model (paper 001, eq. 9): x'' = b0 u + total disturbance, at its bandwidth.
  family.prediction_model = [](const ControllerContext& context, std::size_t axis) {
    const control::AdrcGains gains = read_adrc_gains(context.gains, axis);
    control::PredictionModel model;
    model.damping_per_s = 0.0;
    model.input_gain = gains.input_gain;
    model.observer_bandwidth_rad_s = gains.observer_bandwidth;
    return model;
  };
  registry.add(std::move(family));
}

}  // namespace netmc::job
