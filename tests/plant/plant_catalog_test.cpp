#include "plant/plant_catalog.hpp"
#include "plant/plant_registry.hpp"
#include "plant/second_order_axis.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace netmc::plant {
namespace {

// The test suite's build registers its own plant too (tests/components/test_mass_plant.cpp),
// after the built-in ones.
std::vector<std::string> built_in(std::vector<std::string> names) {
  names.erase(std::remove(names.begin(), names.end(), "test-mass"), names.end());
  return names;
}

TEST(PlantCatalog, Names) {
  EXPECT_EQ(built_in(plant_names()),
            (std::vector<std::string>{"seed001", "ballscrew", "linmotor", "stage004", "linmotor-flex", "hiwin"}));
}

TEST(PlantCatalog, UnknownNameListsTheKnownOnes) {
  try {
    make_plant_set("x", 2);
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    const std::string built_in_names = "seed001, ballscrew, linmotor, stage004, linmotor-flex, hiwin";
    EXPECT_TRUE(std::string(e.what()) == "plant: unknown name 'x' (expected one of: " + built_in_names + ")" ||
                std::string(e.what()) == "plant: unknown name 'x' (expected one of: " + built_in_names + ", test-mass)")
        << e.what();
  }
}

// docs/plants.md carries the table netmc sim --list-plants prints (the test suite's build prints
// its own plant's row too).
TEST(PlantCatalog, TheDocsTableIsTheRegistrys) {
  std::ifstream file(std::string(NETMC_TEST_DATA_DIR) + "/../../docs/plants.md");
  ASSERT_TRUE(file) << "docs/plants.md";
  std::stringstream docs;
  docs << file.rdbuf();
  std::string table;
  std::istringstream lines(PlantRegistry::global().markdown_table());
  for (std::string line; std::getline(lines, line);) {
    if (line.find("`test-mass`") == std::string::npos) table += line + "\n";
  }
  EXPECT_NE(docs.str().find(table), std::string::npos)
      << "docs/plants.md lacks the registry's table; netmc sim --list-plants prints it:\n"
      << table;
}

// Each model's descriptor agrees with what it builds: a travel window and a rated input, and a
// nominal model, where given, that is the built axis's response (the velocity after 1 ms of a
// unit command from rest, in closed form, within the friction's share).
TEST(PlantCatalog, EveryDescriptorMatchesWhatItBuilds) {
  for (const auto& model : PlantRegistry::global().models()) {
    SCOPED_TRACE(model.name);
    EXPECT_LT(model.rating.travel_min_m, model.rating.travel_max_m);
    EXPECT_GT(model.rating.rated_input, 0.0);
    EXPECT_FALSE(model.title.empty());
    EXPECT_FALSE(model.source.empty());
    if (!model.nominal_model) continue;
    const NominalAxisModel nominal = model.nominal_model(0);
    auto axis = model.make_axis(0, nullptr);
    axis->reset(0.0, 0.0);
    const double h = 1e-3;
    axis->advance(h, 1.0);
    // x' after h from rest under u = 1: (b u - c) (1 - e^{a h}) / (-a), or (b u - c) h for a = 0.
    const double drive = nominal.input_gain - nominal.coulomb_m_s2;
    const double expected = nominal.damping_per_s == 0.0
                                ? drive * h
                                : drive * (1.0 - std::exp(nominal.damping_per_s * h)) / -nominal.damping_per_s;
    EXPECT_NEAR(axis->velocity(), expected, 0.02 * std::abs(expected) + nominal.coulomb_m_s2 * h);
  }
}

TEST(PlantCatalog, AxisCountMustBeOneToThree) {
  EXPECT_THROW(make_plant_set("seed001", 0), std::invalid_argument);
  EXPECT_THROW(make_plant_set("seed001", 4), std::invalid_argument);
  EXPECT_THROW(seed001_axis_parameters(3), std::invalid_argument);
}

TEST(PlantCatalog, Seed001AxesHaveTheAssumedDynamicsAndOpposingFriction) {
  // netmc's assumption [A]: speed-mode servos, X 20/(s+20), Y 10/(s+10) from command to velocity.
  const auto x = seed001_axis_parameters(0);
  EXPECT_EQ(x.a1, 0.0);
  EXPECT_EQ(x.a2, -20.0);
  EXPECT_EQ(x.b, 20.0);
  const auto y = seed001_axis_parameters(1);
  EXPECT_EQ(y.a2, -10.0);
  EXPECT_EQ(y.b, 10.0);
  // Friction (calibrated, see the catalog) always opposes motion: a coasting axis slows down
  // faster than its viscous term alone would make it.
  for (std::size_t axis = 0; axis < 3; ++axis) {
    SecondOrderAxis plant(seed001_axis_parameters(axis));
    plant.reset(0.0, 0.01);
    plant.advance(0.01, 0.0);
    const double viscous_only = 0.01 * std::exp(seed001_axis_parameters(axis).a2 * 0.01);
    EXPECT_LT(plant.velocity(), viscous_only) << axis;
  }
  EXPECT_EQ(seed001_axis_parameters(2).coulomb_acceleration, y.coulomb_acceleration);
}

TEST(PlantCatalog, EverySetIsFiniteAndBoundedAfterOneSecondAtRest) {
  for (const std::string& name : plant_names()) {
    for (std::size_t count = 1; count <= 3; ++count) {
      AxisSet set = make_plant_set(name, count);
      ASSERT_EQ(set.axes.size(), count) << name;
      EXPECT_NE(set.description.find(name), std::string::npos) << set.description;
      for (auto& axis : set.axes) {
        axis->reset(0.0, 0.0);
        for (int k = 0; k < 1000; ++k) axis->advance(1e-3, 0.0);
        EXPECT_TRUE(std::isfinite(axis->position())) << name;
        EXPECT_TRUE(std::isfinite(axis->velocity())) << name;
        EXPECT_LT(std::abs(axis->position()), 0.05) << name;  // cogging may nudge linmotor
        EXPECT_LT(std::abs(axis->velocity()), 0.1) << name;
        EXPECT_NEAR(axis->time(), 1.0, 1e-12) << name;
      }
      if (count == 3) {
        EXPECT_EQ(set.axes[2]->describe(), set.axes[1]->describe()) << name;
        // paper 002 uses the same parameters on both axes; hiwin is a single axis, copied; the
        // test suite's test-mass is one model for every axis
        if (name != "ballscrew" && name != "hiwin" && name != "test-mass") {
          EXPECT_NE(set.axes[0]->describe(), set.axes[1]->describe()) << name;
        }
      }
    }
  }
}

TEST(PlantCatalog, SetsAreDrivenByAnInput) {
  // A positive input moves every axis forward (sanity of signs and units).
  for (const std::string& name : plant_names()) {
    AxisSet set = make_plant_set(name, 2);
    // N for the stage, V (or b u) else; hiwin's dead zone swallows 1 V (b_r = 1.2 V)
    const double input = name == "stage004" ? 10.0 : name == "hiwin" ? 2.0 : 1.0;
    for (auto& axis : set.axes) {
      axis->reset(0.0, 0.0);
      for (int k = 0; k < 100; ++k) axis->advance(1e-3, input);
      EXPECT_GT(axis->position(), 0.0) << name;
      EXPECT_GT(axis->velocity(), 0.0) << name;
    }
  }
}

// Thesis 5.5: any plant takes an input dead zone per axis; the axis with one does not move for a
// held input inside the gap and moves as the plain axis does for the input shifted by b_r.
TEST(PlantCatalog, AnyPlantTakesAnInputDeadZonePerAxis) {
  for (const auto& name : plant_names()) {
    const auto keys = plant_parameters(name);
    EXPECT_NE(std::find_if(keys.begin(), keys.end(), [](const auto& k) { return k.key == "dead_zone_left_slope"; }),
              keys.end())
        << name;
  }
  AxisOverrides x, no_cogging;  // the cogging force would move the axis at rest
  no_cogging.parameters = {{"cogging_scale", 0.0}};
  x.parameters = {{"cogging_scale", 0.0}, {"dead_zone_right_v", 0.3}, {"dead_zone_left_v", -0.25},
                  {"dead_zone_right_slope", 1.0}};
  auto with = make_plant_set("linmotor", 2, {x, no_cogging});
  auto plain = make_plant_set("linmotor", 2, {no_cogging, no_cogging});
  with.axes[0]->advance(0.5, 0.29);  // in the gap
  EXPECT_EQ(with.axes[0]->position(), 0.0);
  with.axes[0]->reset(0.0, 0.0);
  with.axes[0]->advance(0.3, 1.3);
  plain.axes[0]->advance(0.3, 1.0);
  EXPECT_NEAR(with.axes[0]->position(), plain.axes[0]->position(), 1e-12);
  EXPECT_GT(with.axes[0]->position(), 1e-3);
  // Y has none: the same as the plain Y.
  with.axes[1]->advance(0.3, 0.2);
  plain.axes[1]->advance(0.3, 0.2);
  EXPECT_EQ(with.axes[1]->position(), plain.axes[1]->position());
  AxisOverrides bad;
  bad.parameters = {{"dead_zone_left_v", 0.1}};
  try {
    make_plant_set("linmotor", 1, {bad});
    ADD_FAILURE() << "accepted a left break point above 0";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("left_break_v"), std::string::npos) << error.what();
  }
}

TEST(PlantCatalog, ClonePreservesStateForEveryPlantType) {
  for (const std::string& name : plant_names()) {
    AxisSet set = make_plant_set(name, 2);
    for (auto& axis : set.axes) {
      axis->reset(0.001, 0.002);
      for (int k = 0; k < 7; ++k) axis->advance(1e-3, 0.3 * k);
      auto copy = axis->clone();
      EXPECT_EQ(copy->position(), axis->position()) << name;
      EXPECT_EQ(copy->velocity(), axis->velocity()) << name;
      EXPECT_EQ(copy->time(), axis->time()) << name;
      EXPECT_EQ(copy->describe(), axis->describe()) << name;
      for (int k = 0; k < 5; ++k) {
        copy->advance(7e-4, -0.2);
        axis->advance(7e-4, -0.2);
      }
      EXPECT_EQ(copy->position(), axis->position()) << name;
      EXPECT_EQ(copy->velocity(), axis->velocity()) << name;
      copy->reset(1.0, 0.0);
      EXPECT_NE(axis->position(), 1.0) << name;
    }
  }
}

}  // namespace
}  // namespace netmc::plant
