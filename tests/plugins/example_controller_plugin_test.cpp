// The example component plugin (examples/controller_plugin), built here as a researcher builds
// it: its PD loop gives, on a closed loop of paper 001's axis, every command of netmc's own PID
// loop with ki = 0 to the last bit; its servo axis moves as seed001's without friction, to the
// last bit; its keys, its refusals (with its own messages, prefixed by the path) and a job's
// per-axis parameters over the spec's.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

#include "control/axis/pid_axis_controller.hpp"
#include "plant/plant_catalog.hpp"
#include "plant/second_order_axis.hpp"
#include "server/plugins/plugin_component_factories.hpp"

namespace netmc::plugins {
namespace {

const std::string kExample = NETMC_TEST_COMPONENT_EXAMPLE;

template <typename Call>
std::string thrown(Call&& call) {
  try {
    call();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

// A reference that moves and rests: a step, a ramp, then a sine (m).
double reference_at(int k, double h) {
  const double t = k * h;
  if (t < 0.3) return 1e-3;
  if (t < 0.8) return 1e-3 + 4e-3 * (t - 0.3);
  return 3e-3 + 1e-3 * std::sin(2.0 * std::numbers::pi * 1.5 * (t - 0.8));
}

// Runs the plugin's loop and netmc's PID (ki = 0) side by side, each on its own seed001 X axis
// (with friction), for 2000 samples; every command and position must be the same double.
void expect_same_loop(const std::string& spec, const control::PidAxisGains& gains, const PluginSettings& axis_settings) {
  const double h = 1e-3;
  auto plugin = make_plugin_axis_controller(spec, 0, h, axis_settings);
  control::PidAxisController builtin(gains, h);
  plant::SecondOrderAxis plugin_axis(plant::seed001_axis_parameters(0));
  plant::SecondOrderAxis builtin_axis(plant::seed001_axis_parameters(0));
  plugin->reset(0.0);
  builtin.reset(0.0);
  plugin_axis.reset(0.0, 0.0);
  builtin_axis.reset(0.0, 0.0);
  int nonzero = 0;
  for (int k = 0; k < 2000; ++k) {
    const double r = reference_at(k, h);
    const double u_plugin = plugin->command(r, plugin_axis.position());
    const double u_builtin = builtin.command(r, builtin_axis.position());
    EXPECT_EQ(u_plugin, u_builtin) << "sample " << k;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(u_plugin), std::bit_cast<std::uint64_t>(u_builtin)) << "sample " << k;
    if (u_plugin != u_builtin) return;
    nonzero += u_plugin != 0.0;
    plugin->commit(r, plugin_axis.position(), u_plugin, u_plugin);
    builtin.commit(r, builtin_axis.position(), u_builtin, u_builtin);
    plugin_axis.advance(h, u_plugin);
    builtin_axis.advance(h, u_builtin);
    ASSERT_EQ(plugin_axis.position(), builtin_axis.position()) << "sample " << k;
  }
  EXPECT_GT(nonzero, 1900);
  EXPECT_NEAR(plugin_axis.position(), reference_at(1999, h), 1e-3);  // it does track
}

TEST(ExampleControllerPlugin, ItsPdLoopGivesEveryCommandOfNetmcsPidWithKiZero) {
  expect_same_loop(kExample + ":kp=400,kd=40", {.kp = 400.0, .ki = 0.0, .kd = 40.0}, {});
  expect_same_loop(kExample + ":kp=250.5,kd=3.25", {.kp = 250.5, .ki = 0.0, .kd = 3.25}, {});
}

TEST(ExampleControllerPlugin, AnAxissOwnSettingsGoOverTheSpecs) {
  expect_same_loop(kExample + ":kp=400,kd=40", {.kp = 400.0, .ki = 0.0, .kd = 25.0}, {{"kd", 25.0}});
  expect_same_loop(kExample + ":kp=400", {.kp = 400.0, .ki = 0.0, .kd = 10.0}, {{"kd", 10.0}});
}

TEST(ExampleControllerPlugin, DescribesItsLoop) {
  EXPECT_EQ(make_plugin_axis_controller(kExample + ":kp=400,kd=40", 1, 1e-3)->describe(), "example pd(kp=400, kd=40)");
}

TEST(ExampleControllerPlugin, RefusesWithItsOwnMessagesPrefixedByThePath) {
  const std::string prefix = "plugin " + kExample + ": ";
  EXPECT_EQ(thrown([&] { make_plugin_axis_controller(kExample + ":kp=400,kd=40,ki=1", 0, 1e-3); }),
            prefix + "example pd: unknown key 'ki' (it takes kp, kd)");
  EXPECT_EQ(thrown([&] { make_plugin_axis_controller(kExample + ":kd=40", 0, 1e-3); }),
            prefix + "example pd: kp is required");
  EXPECT_EQ(thrown([&] { make_plugin_axis_controller(kExample + ":kp=400,kd=40", 0, 0.0); }),
            prefix + "example pd: the sample period must be positive and finite");
  EXPECT_EQ(thrown([&] { make_plugin_axis_controller(kExample + ":kp=fast", 0, 1e-3); }),
            "plugin: the value of kp, 'fast', is not a finite decimal number");
  EXPECT_EQ(thrown([&] { make_plugin_axis_controller(kExample + ":kp=1", 0, 1e-3, {{"k d", 1.0}}); }),
            "plugin: axis X: key 'k d' is empty, too long or has a character other than A-Z a-z 0-9 _ . -");
  EXPECT_EQ(thrown([&] { make_plugin_axis_controller(kExample + ":kp=1", 1, 1e-3, {{"kd", NAN}}); }),
            "plugin: axis Y: kd must be finite (got nan)");
}

// seed001 without friction, the set netmc makes itself.
plant::AxisSet seed001_without_friction(std::size_t axis_count) {
  std::vector<plant::AxisOverrides> overrides(axis_count);
  for (auto& axis : overrides) axis.parameters = {{"coulomb_m_s2", 0.0}};
  return plant::make_plant_set("seed001", axis_count, overrides);
}

TEST(ExampleControllerPlugin, ItsServoAxesMoveAsSeed001sWithoutFriction) {
  auto plugin = make_plugin_plant_set(kExample, 3, {});
  auto builtin = seed001_without_friction(3);
  ASSERT_EQ(plugin.axes.size(), 3u);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(plugin.axes[axis]->describe(), builtin.axes[axis]->describe());
    for (int k = 0; k < 2000; ++k) {
      const double u = 0.5 * std::sin(0.01 * k) + (k % 200 < 100 ? 0.2 : -0.2);
      plugin.axes[axis]->advance(1e-3, u);
      builtin.axes[axis]->advance(1e-3, u);
      ASSERT_EQ(plugin.axes[axis]->position(), builtin.axes[axis]->position()) << "axis " << axis << " sample " << k;
      ASSERT_EQ(plugin.axes[axis]->velocity(), builtin.axes[axis]->velocity()) << "axis " << axis << " sample " << k;
    }
    EXPECT_EQ(plugin.axes[axis]->time(), builtin.axes[axis]->time());
  }
  EXPECT_EQ(plugin.description.rfind("plugin:" + kExample +
                                         " (netmc example: PD axis loop (kp, kd) and paper 001's servo axis x'' = a2 x' "
                                         "+ b u (a2, b)) | X: SecondOrderAxis (paper 001 eq. 3): a1=0 1/s^2, a2=-20 1/s",
                                     0),
            0u)
      << plugin.description;
  EXPECT_NE(plugin.description.find(" | Z: SecondOrderAxis (paper 001 eq. 3): a1=0 1/s^2, a2=-10 1/s, b=10,"),
            std::string::npos)
      << plugin.description;
}

TEST(ExampleControllerPlugin, AJobsPerAxisParametersGoOverTheSpecs) {
  std::vector<plant::AxisOverrides> overrides(2);
  overrides[1].parameters = {{"b", 5.0}, {"a2", -30.0}, {"b", 7.0}};  // in order: the last b wins
  auto set = make_plugin_plant_set(kExample + ":a2=-12", 2, overrides);
  EXPECT_NE(set.axes[0]->describe().find("a2=-12 1/s, b=20,"), std::string::npos) << set.axes[0]->describe();
  EXPECT_NE(set.axes[1]->describe().find("a2=-30 1/s, b=7,"), std::string::npos) << set.axes[1]->describe();
}

TEST(ExampleControllerPlugin, RefusesABadPlantSettingADisturbanceAndABadAxisCount) {
  const std::string prefix = "plugin " + kExample + ": ";
  EXPECT_EQ(thrown([&] { make_plugin_plant_set(kExample + ":c=1", 1, {}); }),
            prefix + "example servo axis: unknown key 'c' (it takes a2, b)");
  std::vector<plant::AxisOverrides> overrides(2);
  overrides[1].parameters = {{"b", -1.0}};
  EXPECT_EQ(thrown([&] { make_plugin_plant_set(kExample, 2, overrides); }),
            prefix + "example servo axis: b must be positive");
  overrides[1].parameters.clear();
  overrides[1].disturbance.constant = 0.1;
  EXPECT_EQ(thrown([&] { make_plugin_plant_set(kExample, 2, overrides); }),
            prefix + "axis Y has a disturbance; a plugin plant takes none from netmc (model it in the plugin)");
  EXPECT_EQ(thrown([&] { make_plugin_plant_set(kExample, 4, {}); }), "plant: axis_count must be 1, 2 or 3 (got 4)");
  EXPECT_EQ(thrown([&] { make_plugin_plant_set(kExample, 1, overrides); }), "plant: overrides for 2 axes, the set has 1");
}

TEST(ExampleControllerPlugin, RefusesAPluginThatProvidesNothingAsAPlantSet) {
  EXPECT_EQ(thrown([&] { make_plugin_plant_set(NETMC_TEST_COMPONENT_NOTHING, 1, {}); }),
            std::string("plugin ") + NETMC_TEST_COMPONENT_NOTHING +
                ": it provides nothing: its make_axis_controller and make_plant are both null");
}

}  // namespace
}  // namespace netmc::plugins
