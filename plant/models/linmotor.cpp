// linmotor -- paper 000 (thesis), eq. 2-43 with appendix A nominals (A.8/A.9) in volts:
//   X: M = 0.12 V/(m/s^2), B = 0.3 V/(m/s), A = 0.1 V;
//   Y: M = 0.55 (the Set1 value of sections 3.5.3 and 4.4.2, rather than the 0.5 nominal of A.9),
//      B = 0.4, A = 0.15 V.
//   Cogging, eq. 4-2/4-23 with the measured pitch P = 50 mm, X harmonics 1, 2, 3 and Y harmonics
//   1, 6, 12; the amplitudes are only in Figs. 4-3 and 4-4, so netmc assumes [A]:
//   X (S, C) = (0.05, 0.03), (0.02, -0.01), (0.01, 0.01) V;
//   Y (S, C) = (0.04, -0.02), (0.03, 0.02), (0.015, -0.01) V.
//   Stribeck extra friction is left at 0: eq. A.3 gives its form, the thesis no level.
//   Friction smoothing 1e-4 m/s (the thesis' S_f = 2/pi atan(9000 v) has a similar width);
//   sub-step 2e-5 s keeps RK4 stable on the friction slope A/(M v_s) ~ 8300 1/s (X).
// Rating (linmotor and linmotor-flex): thesis appendix A's 500 x 500 mm travel, -0.25..0.25 m;
//   +-10 V, the DS1103 outputs to the amplifiers (force linear to about 8 V) [chapter 2-4 runs
//   reach 30-50 V in their first cycles: the thesis simulates them unsaturated].
#include "plant/models/linear_motor_nominals.hpp"
#include "plant/plant_registry.hpp"

namespace netmc::plant {

LinearMotorParameters linmotor_axis_parameters(std::size_t axis) {
  LinearMotorParameters p;
  p.cogging_pitch_m = 0.05;
  if (axis == 0) {
    p.mass = 0.12;
    p.damping = 0.3;
    p.coulomb = 0.1;
    p.cogging = {{0.05, 0.03, 1}, {0.02, -0.01, 2}, {0.01, 0.01, 3}};
  } else {
    p.mass = 0.55;
    p.damping = 0.4;
    p.coulomb = 0.15;
    p.cogging = {{0.04, -0.02, 1}, {0.03, 0.02, 6}, {0.015, -0.01, 12}};
  }
  return p;
}

std::vector<PlantSetting<LinearMotorParameters>> linmotor_settings() {
  using P = LinearMotorParameters;
  return {
      {"mass_v_s2_m", "M, moving mass (V/(m/s^2)); X 0.12, Y 0.55", [](P& p, double v) { p.mass = v; }},
      {"load_v_s2_m", "payload mass added to M (V/(m/s^2)); 0",
       [](P& p, double v) {
         require_non_negative_value("load_v_s2_m", v);
         p.mass += v;
       }},
      {"damping_v_s_m", "B, viscous friction (V/(m/s)); X 0.3, Y 0.4", [](P& p, double v) { p.damping = v; }},
      {"coulomb_v", "A, Coulomb friction (V); X 0.1, Y 0.15", [](P& p, double v) { p.coulomb = v; }},
      {"stribeck_extra_v", "static minus Coulomb friction (V); 0", [](P& p, double v) { p.stribeck_extra = v; }},
      {"stribeck_velocity_m_s", "Stribeck velocity (m/s); 0.01", [](P& p, double v) { p.stribeck_velocity = v; }},
      {"cogging_scale", "factor on every cogging amplitude; 1",
       [](P& p, double v) {
         for (auto& harmonic : p.cogging) {
           harmonic.sine *= v;
           harmonic.cosine *= v;
         }
       }},
  };
}

void register_linmotor(PlantRegistry& registry) {
  PlantModel model;
  model.name = "linmotor";
  model.title = "paper 000 linear motors (X/Y nominals, friction, cogging [A])";
  model.source = "paper 000 (thesis)";
  model.input_unit = "V";
  model.rating = {-0.25, 0.25, 10.0};
  model.parameters = describe_settings(linmotor_settings());
  model.make_axis = [](std::size_t axis, const AxisOverrides* overrides) -> std::unique_ptr<AxisPlant> {
    return std::make_unique<LinearMotorAxis>(
        with_overrides(linmotor_axis_parameters(axis), linmotor_settings(), overrides, "linmotor"));
  };
  registry.add(std::move(model));
}

}  // namespace netmc::plant
