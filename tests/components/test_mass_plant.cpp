// A plant of the test suite's own, added the way a researcher adds one: this file (the model and
// its descriptor) and one registration line in plant/models/registered_plants.inc. Built only
// with -DNETMC_TEST_COMPONENTS=ON (the test suite's build, scripts/test.sh), so installed netmc
// does not carry it; integration.own_controller runs it in netmc sim and over DDS.
//
// The model: a mass on a viscous guide driven by a force, m x'' = u - c x' (SI), nominal m = 0.05
// kg, c = 1 N s/m, so x'' = 20 u - 20 x': seed001's X axis without its friction.
#include <memory>
#include <stdexcept>
#include <string>

#include "plant/plant_registry.hpp"
#include "plant/plant_settings.hpp"
#include "plant/second_order_axis.hpp"

namespace netmc::plant {
namespace {

struct TestMassParameters {
  double mass_kg = 0.05;
  double damping_n_s_m = 1.0;
  Disturbance disturbance;  // N
};

std::vector<PlantSetting<TestMassParameters>> test_mass_settings() {
  using P = TestMassParameters;
  return {
      {"mass_kg", "m, moving mass (kg); 0.05",
       [](P& p, double v) {
         if (!(v > 0.0)) throw std::invalid_argument("plant: mass_kg must be > 0 (got " + std::to_string(v) + ")");
         p.mass_kg = v;
       }},
      {"damping_n_s_m", "c, viscous damping (N s/m); 1",
       [](P& p, double v) {
         require_non_negative_value("damping_n_s_m", v);
         p.damping_n_s_m = v;
       }},
  };
}

std::unique_ptr<AxisPlant> make_test_mass_axis(const TestMassParameters& p) {
  SecondOrderAxisParameters axis;
  axis.a1 = 0.0;
  axis.a2 = -p.damping_n_s_m / p.mass_kg;
  axis.b = 1.0 / p.mass_kg;
  axis.coulomb_acceleration = 0.0;
  axis.disturbance = scaled(p.disturbance, 1.0 / p.mass_kg);  // N -> m/s^2
  return std::make_unique<SecondOrderAxis>(axis);
}

}  // namespace

void register_test_mass(PlantRegistry& registry) {
  registry.add(PlantModel{
      .name = "test-mass",
      .title = "the test suite's mass on a viscous guide (tests/components)",
      .source = "textbook: Newton's second law with viscous friction",
      .input_unit = "N",
      .rating = {-0.1, 0.2, 5.0},
      .own_dead_zone = false,
      .parameters = describe_settings(test_mass_settings()),
      .make_axis = [](std::size_t, const AxisOverrides* overrides) -> std::unique_ptr<AxisPlant> {
        return make_test_mass_axis(with_overrides(TestMassParameters{}, test_mass_settings(), overrides, "test-mass"));
      },
      .nominal_model =
          [](std::size_t) {
            const TestMassParameters p;
            return NominalAxisModel{-p.damping_n_s_m / p.mass_kg, 1.0 / p.mass_kg, 0.0, 1e-3};
          },
  });
}

}  // namespace netmc::plant
