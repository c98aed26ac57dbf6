// FmuAxisPlant through the AxisPlant interface: reset, advance(0), clone (right after reset,
// advanced, of a prototype that was never used, the emulated drive's probe), several instances,
// the estimated velocity, a fixed-step FMU, describe(), the private directory and the logger.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "server/fmu/fmu_logger.hpp"
#include "plant/plant_catalog.hpp"
#include "plant/second_order_axis.hpp"
#include "test_fmu.hpp"

namespace netmc::plant::fmu {
namespace {

using test::as_fmu;
using test::fmu_axis;
using test::message_of;

const std::string kAxis = NETMC_TEST_FMU_SEED001_AXIS;

double input_at(int k) { return 0.5 * std::sin(0.21 * k) + 0.2; }

void expect_same_state(const AxisPlant& a, const AxisPlant& b) {
  EXPECT_EQ(a.position(), b.position());
  EXPECT_EQ(a.velocity(), b.velocity());
  EXPECT_EQ(a.time(), b.time());
}

TEST(FmuAxisPlant, StartsWhereTheFmuStartValuesPutItAndHoldsNoInstanceUntilUsed) {
  auto plant = fmu_axis(kAxis, ":x0=0.003,v0=-0.001,velocity=v");
  EXPECT_FALSE(as_fmu(*plant).instantiated());
  EXPECT_EQ(plant->position(), 0.003);
  EXPECT_EQ(plant->velocity(), -0.001);
  EXPECT_EQ(plant->time(), 0.0);
  plant->advance(1e-3, 0.0);
  EXPECT_TRUE(as_fmu(*plant).instantiated());
  EXPECT_NE(plant->position(), 0.003);
}

TEST(FmuAxisPlant, ResetSetsPositionVelocityAndTime) {
  auto plant = fmu_axis(kAxis, ":velocity=v");
  plant->advance(0.01, 1.0);
  plant->reset(0.025, 0.004);
  EXPECT_EQ(plant->position(), 0.025);
  EXPECT_EQ(plant->velocity(), 0.004);
  EXPECT_EQ(plant->time(), 0.0);
  // The same run from the same reset gives the same numbers.
  auto fresh = fmu_axis(kAxis, ":velocity=v");
  fresh->reset(0.025, 0.004);
  for (int k = 0; k < 50; ++k) {
    plant->advance(1e-3, input_at(k));
    fresh->advance(1e-3, input_at(k));
  }
  expect_same_state(*plant, *fresh);
  // Again after a second reset of the same plant.
  plant->reset(0.025, 0.004);
  auto again = fmu_axis(kAxis, ":velocity=v");
  again->reset(0.025, 0.004);
  for (int k = 0; k < 50; ++k) {
    plant->advance(2e-3, input_at(k));
    again->advance(2e-3, input_at(k));
  }
  expect_same_state(*plant, *again);
}

TEST(FmuAxisPlant, DurationZeroIsANoOp) {
  auto plant = fmu_axis(kAxis, ":velocity=v");
  plant->advance(0.0, 3.0);
  EXPECT_FALSE(as_fmu(*plant).instantiated());  // nothing was called, not even fmi2Instantiate
  plant->reset(0.01, 0.002);
  plant->advance(5e-3, 1.0);
  const double x = plant->position(), v = plant->velocity(), t = plant->time();
  plant->advance(0.0, -7.0);
  EXPECT_EQ(plant->position(), x);
  EXPECT_EQ(plant->velocity(), v);
  EXPECT_EQ(plant->time(), t);
  EXPECT_THROW(plant->advance(-1e-3, 0.0), std::invalid_argument);
  EXPECT_THROW(plant->advance(1e-3, std::nan("")), std::invalid_argument);
}

TEST(FmuAxisPlant, CloneRightAfterResetEqualsTheOriginal) {
  auto plant = fmu_axis(kAxis, ":velocity=v");
  plant->reset(0.04, 0.001);
  auto copy = plant->clone();
  expect_same_state(*plant, *copy);
  for (int k = 0; k < 200; ++k) {
    plant->advance(0.7e-3, input_at(k));
    copy->advance(0.7e-3, input_at(k));
  }
  expect_same_state(*plant, *copy);
  EXPECT_EQ(copy->describe(), plant->describe());
}

TEST(FmuAxisPlant, AnAdvancedCloneDoesNotMoveTheOriginal) {
  auto plant = fmu_axis(kAxis, ":velocity=v");
  plant->reset(0.0, 0.0);
  for (int k = 0; k < 300; ++k) plant->advance(k % 3 == 0 ? 0.4e-3 : 1.6e-3, input_at(k));
  auto copy = plant->clone();
  expect_same_state(*plant, *copy);  // the same current state, bit for bit
  const double x = plant->position(), v = plant->velocity(), t = plant->time();
  for (int k = 0; k < 100; ++k) copy->advance(1e-3, 2.0);
  EXPECT_EQ(plant->position(), x);
  EXPECT_EQ(plant->velocity(), v);
  EXPECT_EQ(plant->time(), t);
  EXPECT_NE(copy->position(), x);
  // And the original, driven alike, lands where the clone did.
  for (int k = 0; k < 100; ++k) plant->advance(1e-3, 2.0);
  expect_same_state(*plant, *copy);
}

TEST(FmuAxisPlant, ACloneOfAnUnusedPrototypeIsUnusedTooAndTheProbePatternWorks) {
  // server/sim/axis_endpoint.cpp clones the job's prototypes; server/drive/emulated_drive.cpp
  // clones its plant, resets the copy at rest and pushes it for 2 ms.
  auto prototype = fmu_axis(kAxis, ":velocity=v");
  auto drive_plant = prototype->clone();
  EXPECT_FALSE(as_fmu(*drive_plant).instantiated());
  double velocity[2];
  for (int sign = 0; sign < 2; ++sign) {
    auto probe = drive_plant->clone();
    probe->reset(0.0, 0.0);
    probe->advance(0.002, sign == 0 ? 10.0 : -10.0);
    velocity[sign] = probe->velocity();
  }
  EXPECT_GT(velocity[0], 0.0);
  EXPECT_LT(velocity[1], 0.0);
  EXPECT_FALSE(as_fmu(*prototype).instantiated());
  EXPECT_FALSE(as_fmu(*drive_plant).instantiated());
  EXPECT_EQ(drive_plant->position(), 0.0);
}

TEST(FmuAxisPlant, SeveralInstancesAreIndependent) {
  // Three axes of one set (one loaded model), each with its parameters, driven differently, each
  // against its own built-in axis; and a second set of the same file beside them.
  std::vector<AxisOverrides> overrides(3);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const SecondOrderAxisParameters p = seed001_axis_parameters(axis);
    overrides[axis].parameters = {{"a2", p.a2}, {"b", p.b}, {"coulomb", p.coulomb_acceleration}};
  }
  AxisSet set = make_fmu_plant_set(kAxis + ":velocity=v", 3, overrides);
  AxisSet other = make_fmu_plant_set(kAxis + ":velocity=v", 1, {overrides[0]});
  ASSERT_EQ(set.axes.size(), 3u);
  std::vector<std::unique_ptr<AxisPlant>> references;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    references.push_back(std::make_unique<SecondOrderAxis>(seed001_axis_parameters(axis)));
  }
  references.push_back(std::make_unique<SecondOrderAxis>(seed001_axis_parameters(0)));
  std::vector<AxisPlant*> plants{set.axes[0].get(), set.axes[1].get(), set.axes[2].get(), other.axes[0].get()};
  for (std::size_t i = 0; i < plants.size(); ++i) {
    plants[i]->reset(0.01 * static_cast<double>(i), 0.0);
    references[i]->reset(0.01 * static_cast<double>(i), 0.0);
  }
  for (int k = 0; k < 400; ++k) {
    for (std::size_t i = 0; i < plants.size(); ++i) {
      const double input = (i % 2 == 0 ? 1.0 : -1.0) * input_at(k + 17 * static_cast<int>(i));
      plants[i]->advance(1e-3, input);
      references[i]->advance(1e-3, input);
    }
  }
  for (std::size_t i = 0; i < plants.size(); ++i) {
    EXPECT_NEAR(plants[i]->position(), references[i]->position(), 1e-9 * 0.05) << "axis " << i;
    EXPECT_NEAR(plants[i]->velocity(), references[i]->velocity(), 1e-6 * 0.05) << "axis " << i;
  }
}

TEST(FmuAxisPlant, WithoutAVelocityOutputTheVelocityIsTheDifferenceQuotientOfTheLastStep) {
  auto plant = fmu_axis(kAxis);  // no velocity=: estimated
  plant->reset(0.0, 0.003);      // v0 exists: the start velocity is taken
  EXPECT_EQ(plant->velocity(), 0.003);
  plant->advance(2e-3, 1.0);  // one 1 ms step after another
  const double x1 = plant->position();
  plant->advance(1e-3, 1.0);
  EXPECT_DOUBLE_EQ(plant->velocity(), (plant->position() - x1) / 1e-3);
}

TEST(FmuAxisPlant, AFixedStepFmuTakesWholeNumbersOfItsStepOnly) {
  auto plant = fmu_axis(NETMC_TEST_FMU_FIXED_STEP);
  plant->reset(0.0, 0.0);
  plant->advance(2e-3, 1.0);
  EXPECT_NEAR(plant->time(), 2e-3, 1e-15);
  const std::string message = message_of<std::runtime_error>([&] { plant->advance(1.5e-3, 1.0); });
  EXPECT_NE(message.find("canHandleVariableCommunicationStepSize"), std::string::npos) << message;
}

TEST(FmuAxisPlant, DescribeNamesTheFmuTheModelAndTheOptions) {
  auto plant = fmu_axis(kAxis, ":velocity=v,step=0.5ms,b=12", {{"a2", -15.0}});
  const std::string text = plant->describe();
  for (const char* part : {"seed001_axis.fmu", "'seed001_axis'", "FMI 2.0 co-simulation", "input u", "output x",
                           "velocity v", "step 0.0005 s", "position_start x0", "b=12", "a2=-15"}) {
    EXPECT_NE(text.find(part), std::string::npos) << part << " in " << text;
  }
}

TEST(FmuAxisPlant, AModelAllowedOncePerProcessRunsOneAxisWithLazyPrototypes) {
  auto prototype = fmu_axis(NETMC_TEST_FMU_ONCE_PER_PROCESS, ":velocity=v");
  auto drive_plant = prototype->clone();  // prototype and copy hold no instance
  {
    auto probe = drive_plant->clone();
    probe->reset(0.0, 0.0);
    probe->advance(0.002, 10.0);
  }
  drive_plant->reset(0.0, 0.0);
  drive_plant->advance(0.01, 1.0);
  // A second live instance is what the model forbids.
  auto second = prototype->clone();
  const std::string message = message_of<std::runtime_error>([&] { second->reset(0.0, 0.0); });
  EXPECT_NE(message.find("canBeInstantiatedOnlyOncePerProcess"), std::string::npos) << message;
  EXPECT_THROW(drive_plant->clone(), std::runtime_error);
}

TEST(FmuAxisPlant, UnpacksIntoAPrivateDirectoryRemovedWithTheModel) {
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "netmc-fmu-plant-test-tmpdir";
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root);
  const char* saved = std::getenv("TMPDIR");
  const std::string saved_value = saved ? saved : "";
  ::setenv("TMPDIR", root.c_str(), 1);
  {
    auto plant = fmu_axis(kAxis);
    plant->reset(0.0, 0.0);
    plant->advance(1e-3, 1.0);
    std::vector<std::filesystem::path> made(std::filesystem::directory_iterator(root), {});
    ASSERT_EQ(made.size(), 1u);
    struct stat status {};
    ASSERT_EQ(::stat(made[0].c_str(), &status), 0);
    EXPECT_EQ(status.st_mode & 0777, 0700u);
    EXPECT_TRUE(std::filesystem::exists(made[0] / "model.so"));
    EXPECT_FALSE(std::filesystem::exists(made[0] / "modelDescription.xml"));  // read in memory
  }
  EXPECT_TRUE(std::filesystem::is_empty(root));
  if (saved) {
    ::setenv("TMPDIR", saved_value.c_str(), 1);
  } else {
    ::unsetenv("TMPDIR");
  }
  std::filesystem::remove_all(root);
}

TEST(FmuPlantSet, NamesAndSummary) {
  EXPECT_TRUE(is_fmu_plant("fmu:model.fmu"));
  EXPECT_FALSE(is_fmu_plant("seed001"));
  AxisSet set = make_fmu_plant_set("fmu:" + kAxis, 2);  // the prefix is taken too
  EXPECT_NE(set.description.find("(model 'seed001_axis', FMI 2.0 co-simulation, 2 axes)"), std::string::npos)
      << set.description;
  const FmuPlantSummary summary = summarize_fmu_plant(kAxis + ":b=3");
  EXPECT_EQ(summary.model_name, "seed001_axis");
  EXPECT_EQ(summary.input_unit, "");  // u declares none
  std::vector<std::string> keys;
  for (const auto& p : summary.parameters) keys.push_back(p.key);
  EXPECT_EQ(keys, (std::vector<std::string>{"a1", "a2", "b", "coulomb", "coulomb_velocity_scale", "max_substep", "x0",
                                            "v0"}));
  EXPECT_EQ(summary.parameters[1].description, "FMU parameter (1/s); -20");
  EXPECT_THROW(summarize_fmu_plant(NETMC_TEST_FMU_NOT_A_ZIP), std::invalid_argument);
}

TEST(FmuLogger, WritesWarningsAndErrorsToStderrUpToItsBound) {
  FmuLogger logger("model.fmu", 3);
  testing::internal::CaptureStderr();
  FmuLogger::log(&logger, "axis0", fmi2OK, "logAll", "informational, dropped");
  for (int i = 0; i < 10; ++i) FmuLogger::log(&logger, "axis0", fmi2Warning, "logStatusWarning", "warning %d\n", i);
  const std::string out = testing::internal::GetCapturedStderr();
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 4) << out;
  EXPECT_NE(out.find("fmu model.fmu [axis0] fmi2Warning logStatusWarning: warning 0?"), std::string::npos) << out;
  EXPECT_EQ(out.find("informational"), std::string::npos);
  EXPECT_NE(out.find("suppressed"), std::string::npos);
  EXPECT_EQ(logger.last_message("axis0"), "warning 9?");
}

}  // namespace
}  // namespace netmc::plant::fmu
