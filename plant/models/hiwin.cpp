// hiwin -- paper 000 (thesis) ch. 5, the Hiwin single-axis linear-motor stage, eq. 5-49 with the
//   Exp I dead zone 5-51: x'' = E w - B x' - A S_f(x'), w = D(v), identified B = 4.3 1/s,
//   A = 0.9 m/s^2 (printed "/s"; it multiplies a unit-free S_f), E = 3.6 m/s^2/V, f_N = 0;
//   D: right 0.9 (v - 1.2), left 1.0 (v + 1) (volts in, volts out). Exp II's symmetric dead zone
//   5-54 is dead_zone_left_slope = 0.9.
//   S_f: chapter 5 and appendix A give no form; chapter 3's is 2/pi atan(9000 v). The plant uses
//   SecondOrderAxis's tanh(v / 1.745e-4 m/s), the same slope at v = 0 (2/pi 9000 = 1/1.745e-4).
//   A disturbance (V) enters at the motor, after the dead zone: E times it as an acceleration.
//   Sub-step 5e-5 s: the friction slope A / 1.745e-4 = 5.2e3 1/s gives h lambda = 0.26.
//   A single-axis stage: a second or third axis, when asked for, is a copy.
// Rating [A]: the thesis gives no travel: -0.05..0.45 m around chapter 5's 0-0.4 m; +-10 V
//   [largest |U| of the presets' runs: 3].
#include "plant/dead_zone_input.hpp"
#include "plant/plant_registry.hpp"
#include "plant/plant_settings.hpp"
#include "plant/second_order_axis.hpp"

namespace netmc::plant {
namespace {

// Thesis eq. 5-49 / 5-51 (see above); the dead zone in volts, E applied behind it.
struct HiwinParameters {
  double viscous = 4.3;                  // B (1/s)
  double coulomb = 0.9;                  // A (m/s^2)
  double gain = 3.6;                     // E (m/s^2 per V)
  double friction_velocity_scale = 1.745e-4;  // m/s, tanh width of S_f
  DeadZoneParameters dead_zone{1.2, -1.0, 0.9, 1.0};
  Disturbance disturbance;               // V, at the motor input
  double max_substep_s = 5e-5;
};

std::unique_ptr<AxisPlant> make_hiwin_axis(const HiwinParameters& p) {
  SecondOrderAxisParameters axis;
  axis.a1 = 0.0;
  axis.a2 = -p.viscous;
  axis.b = p.gain;
  axis.coulomb_acceleration = p.coulomb;
  axis.coulomb_velocity_scale = p.friction_velocity_scale;
  axis.disturbance = scaled(p.disturbance, p.gain);  // V -> m/s^2
  axis.max_substep_s = p.max_substep_s;
  return std::make_unique<DeadZoneInput>(p.dead_zone, std::make_unique<SecondOrderAxis>(axis));
}

std::vector<PlantSetting<HiwinParameters>> hiwin_settings() {
  using P = HiwinParameters;
  std::vector<PlantSetting<P>> out = {
      {"viscous_1_s", "B, viscous friction (1/s); 4.3", [](P& p, double v) { p.viscous = v; }},
      {"coulomb_m_s2", "A, Coulomb friction (m/s^2); 0.9", [](P& p, double v) { p.coulomb = v; }},
      {"gain_m_s2_v", "E, motor input gain ((m/s^2)/V); 3.6", [](P& p, double v) { p.gain = v; }},
      {"friction_velocity_scale_m_s", "tanh width of S_f (m/s); 1.745e-4",
       [](P& p, double v) { p.friction_velocity_scale = v; }},
      {"max_substep_s", "RK4 sub-step bound (s); 5e-5", [](P& p, double v) { p.max_substep_s = v; }},
  };
  // Exp I's dead zone (5-51); Exp II's symmetric one (5-54) is dead_zone_left_slope = 0.9.
  for (auto& dead_zone : dead_zone_settings(HiwinParameters{}.dead_zone, "V")) {
    out.push_back({dead_zone.key, dead_zone.description,
                   [apply = dead_zone.apply](P& p, double v) { apply(p.dead_zone, v); }});
  }
  return out;
}

}  // namespace

void register_hiwin(PlantRegistry& registry) {
  PlantModel model;
  model.name = "hiwin";
  model.title = "paper 000 ch. 5 single-axis linear motor with an input dead zone (eq. 5-49, 5-51)";
  model.source = "paper 000 (thesis), ch. 5";
  model.input_unit = "V";
  model.rating = {-0.05, 0.45, 10.0};
  model.own_dead_zone = true;
  model.parameters = describe_settings(hiwin_settings());
  model.make_axis = [](std::size_t, const AxisOverrides* overrides) -> std::unique_ptr<AxisPlant> {
    return make_hiwin_axis(with_overrides(HiwinParameters{}, hiwin_settings(), overrides, "hiwin"));
  };
  registry.add(std::move(model));
}

}  // namespace netmc::plant
