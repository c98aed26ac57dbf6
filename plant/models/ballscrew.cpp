// ballscrew -- paper 002, eq. 1 (section 2) with section 6's parameters, both axes: J = 0.8e-3 kg m^2,
//   B = 0.255 N m s/rad, Ka = 3.2 A/V, Kt = 0.9 N m/A, rg = 5 mm/rad = 0.005 m/rad, giving
//   y'' = -318.75 y' + 18 (u + d) m/s^2 and 56.47 mm/s per volt (derived from eq. 1).
// Rating: paper 002's stroke of 150 mm per axis, 0..0.15 m; [A] +-10 V, the amplifiers' analog
//   input range (Ka in A/V) [the paper's own runs diverge past it].
#include "plant/ball_screw_drive.hpp"
#include "plant/plant_registry.hpp"
#include "plant/plant_settings.hpp"

namespace netmc::plant {
namespace {

std::vector<PlantSetting<BallScrewParameters>> ballscrew_settings() {
  using P = BallScrewParameters;
  return {
      {"inertia_kg_m2", "J, reflected inertia (kg m^2); 0.8e-3", [](P& p, double v) { p.inertia = v; }},
      {"damping_n_m_s_rad", "B, viscous damping (N m s/rad); 0.255", [](P& p, double v) { p.damping = v; }},
      {"amplifier_gain_a_v", "Ka (A/V); 3.2", [](P& p, double v) { p.amplifier_gain = v; }},
      {"torque_constant_n_m_a", "Kt (N m/A); 0.9", [](P& p, double v) { p.torque_constant = v; }},
      {"lead_m_rad", "rg, screw lead (m/rad); 0.005", [](P& p, double v) { p.lead_m_per_rad = v; }},
      // paper 002's load (section 6.3), as netmc assumes [A]: a payload m on the table adds m rg^2 to J
      // (3 kg: 0.875e-3 kg m^2)
      {"load_kg", "payload on the table (kg), adds load * rg^2 to J; 0",
       [](P& p, double v) {
         require_non_negative_value("load_kg", v);
         p.inertia += v * p.lead_m_per_rad * p.lead_m_per_rad;
       }},
  };
}

}  // namespace

void register_ballscrew(PlantRegistry& registry) {
  PlantModel model;
  model.name = "ballscrew";
  model.title = "paper 002 eq. 1 ball-screw drives (nominal J, B, Ka, Kt, rg)";
  model.source = "paper 002";
  model.input_unit = "V";
  model.rating = {0.0, 0.15, 10.0};
  model.parameters = describe_settings(ballscrew_settings());
  model.make_axis = [](std::size_t, const AxisOverrides* overrides) -> std::unique_ptr<AxisPlant> {
    return std::make_unique<BallScrewDrive>(with_overrides(BallScrewParameters{}, ballscrew_settings(), overrides,
                                                           "ballscrew"));
  };
  model.nominal_model = [](std::size_t) {
    // paper 002, eq. 1: y'' = -(B/J) y' + (Ka Kt rg / J) u.
    const BallScrewParameters p;
    return NominalAxisModel{-p.damping / p.inertia,
                            p.amplifier_gain * p.torque_constant * p.lead_m_per_rad / p.inertia, 0.0, 1e-3};
  };
  registry.add(std::move(model));
}

}  // namespace netmc::plant
