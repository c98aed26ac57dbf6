// seed001 -- paper 001, eq. 3. The paper gives no plant numbers; netmc's assumed [A]
//   default is a servo in speed mode, in mm: X a1=0, a2=-20, b=20, d=-50 tanh(x'/0.05) mm/s^2;
//   Y a1=0, a2=-10, b=10, d=-70 tanh(y'/0.05) mm/s^2. In metres the friction becomes
//   0.050 / 0.070 m/s^2 with a velocity scale of 5e-5 m/s; a1, a2, b are unit-free in length
//   (b multiplies the command, whose unit the paper leaves open).
//   Calibrated here (docs/reproductions/paper-001.md, "Plant for paper 001"): velocity scale 1 mm/s and levels 60 / 85
//   mm/s^2 give ADRC-only e_max = 0.083 mm (paper: 0.0811 mm). With the first assumed 0.05 mm/s the
//   friction is almost a step at each velocity reversal; the paper's PD-ILC then stalls at
//   e_max/ADRC = 0.47 after 11 iterations and drifts upwards.
//   Sub-step 1 ms: the stiffest term, the friction slope c/scale = 85 1/s (Y), gives
//   |lambda h| = 0.085; with fifth-order Taylor steps (coulomb_taylor_step.hpp) the study's
//   metrics agree with RK4 at 10 us sub-steps to 7e-9 relative (docs/benchmarks.md).
// Rating [A]: paper 001 gives no machine: travel -0.1..0.2 m around its contours (30-80 mm); rated
//   input 1 (the speed-mode servo's command, 1 m/s at steady state) [largest |U| of the presets'
//   runs: 0.03; 12 in seed001-long-delay's unstable PID-CCC run].
// A third axis copies the second axis's parameters.
#include <stdexcept>
#include <string>

#include "plant/plant_catalog.hpp"
#include "plant/plant_registry.hpp"
#include "plant/plant_settings.hpp"
#include "plant/second_order_axis.hpp"

namespace netmc::plant {
namespace {

std::vector<PlantSetting<SecondOrderAxisParameters>> seed001_settings() {
  using P = SecondOrderAxisParameters;
  return {
      {"a1", "position coefficient a1 (1/s^2); X 0, Y 0", [](P& p, double v) { p.a1 = v; }},
      {"a2", "velocity coefficient a2 (1/s); X -20, Y -10", [](P& p, double v) { p.a2 = v; }},
      {"b", "input gain b ((m/s^2) per input unit); X 20, Y 10", [](P& p, double v) { p.b = v; }},
      {"coulomb_m_s2", "Coulomb friction level (m/s^2); X 0.060, Y 0.085",
       [](P& p, double v) { p.coulomb_acceleration = v; }},
      {"coulomb_velocity_scale_m_s", "tanh width of the friction sign (m/s); 1e-3",
       [](P& p, double v) { p.coulomb_velocity_scale = v; }},
  };
}

}  // namespace

SecondOrderAxisParameters seed001_axis_parameters(std::size_t axis) {
  if (axis > 2) {
    throw std::invalid_argument("plant: seed001 axis must be 0, 1 or 2 (got " +
                                std::to_string(axis) + ")");
  }
  SecondOrderAxisParameters p;
  p.a1 = 0.0;
  p.coulomb_velocity_scale = 1e-3;  // 1 mm/s
  p.max_substep_s = 1e-3;  // see above
  if (axis == 0) {
    p.a2 = -20.0;
    p.b = 20.0;
    p.coulomb_acceleration = 0.060;  // 60 mm/s^2
  } else {
    p.a2 = -10.0;
    p.b = 10.0;
    p.coulomb_acceleration = 0.085;  // 85 mm/s^2
  }
  return p;
}

void register_seed001(PlantRegistry& registry) {
  PlantModel model;
  model.name = "seed001";
  model.title = "paper 001 eq. 3 servo axes (netmc's assumed parameters [A])";
  model.source = "paper 001";
  model.input_unit = "m/s^2";
  model.rating = {-0.1, 0.2, 1.0};
  model.parameters = describe_settings(seed001_settings());
  model.make_axis = [](std::size_t axis, const AxisOverrides* overrides) -> std::unique_ptr<AxisPlant> {
    return std::make_unique<SecondOrderAxis>(
        with_overrides(seed001_axis_parameters(axis), seed001_settings(), overrides, "seed001"));
  };
  model.nominal_model = [](std::size_t axis) {
    const SecondOrderAxisParameters p = seed001_axis_parameters(axis);  // a1 = 0
    return NominalAxisModel{p.a2, p.b, p.coulomb_acceleration, p.coulomb_velocity_scale};
  };
  registry.add(std::move(model));
}

}  // namespace netmc::plant
