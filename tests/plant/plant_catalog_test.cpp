#include "plant/plant_catalog.hpp"
#include "plant/second_order_axis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace netmc::plant {
namespace {

TEST(PlantCatalog, Names) {
  EXPECT_EQ(plant_names(),
            (std::vector<std::string>{"seed001", "ballscrew", "linmotor", "stage004", "linmotor-flex", "hiwin"}));
}

TEST(PlantCatalog, UnknownNameListsTheKnownOnes) {
  try {
    make_plant_set("x", 2);
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "plant: unknown name 'x' (expected one of: seed001, ballscrew, linmotor, stage004, "
              "linmotor-flex, hiwin)");
  }
}

TEST(PlantCatalog, AxisCountMustBeOneToThree) {
  EXPECT_THROW(make_plant_set("seed001", 0), std::invalid_argument);
  EXPECT_THROW(make_plant_set("seed001", 4), std::invalid_argument);
  EXPECT_THROW(seed001_axis_parameters(3), std::invalid_argument);
}

TEST(PlantCatalog, Seed001AxesHaveTheDigestDynamicsAndOpposingFriction) {
  // Digest 1.7 [A]: speed-mode servos, X 20/(s+20), Y 10/(s+10) from command to velocity.
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
        // paper 002 uses the same parameters on both axes; hiwin is a single axis, copied
        if (name != "ballscrew" && name != "hiwin") {
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
