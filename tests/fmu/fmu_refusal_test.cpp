// Every refusal of an FMU plant, one message each: what is wrong with the archive, its
// description, its binary, the options' variables, the set, a reset, and a failing or diverging
// step. None takes the process down.

#include <gtest/gtest.h>

#include <string>

#include "test_fmu.hpp"

namespace netmc::plant::fmu {
namespace {

using test::fmu_axis;
using test::message_of;

const std::string kAxis = NETMC_TEST_FMU_SEED001_AXIS;

// The message of the std::invalid_argument that making a one-axis set of `text` throws.
std::string refusal(const std::string& text, std::vector<AxisOverrides> overrides = {}) {
  return message_of<std::invalid_argument>([&] { make_fmu_plant_set(text, 1, overrides); });
}

#define EXPECT_MESSAGE(message, part) EXPECT_NE((message).find(part), std::string::npos) << (message)

TEST(FmuRefusal, TheArchive) {
  EXPECT_MESSAGE(refusal(NETMC_TEST_FMU_NOT_A_ZIP), "not a zip archive");
  EXPECT_MESSAGE(refusal(NETMC_TEST_FMU_NOT_A_ZIP), "not_a_zip.fmu");  // names the FMU
  EXPECT_MESSAGE(refusal("/nonexistent/model.fmu"), "cannot read it: No such file");
  EXPECT_MESSAGE(refusal(NETMC_TEST_FMU_NO_MODEL_DESCRIPTION), "no modelDescription.xml");
  EXPECT_MESSAGE(refusal(NETMC_TEST_FMU_SYMLINK_XML), "modelDescription.xml is a symbolic link");
  EXPECT_MESSAGE(refusal(NETMC_TEST_FMU_NO_BINARY),
                 "no binaries/linux64/seed001_axis.so: no binary for 64-bit Linux (binaries for: none)");
}

TEST(FmuRefusal, TheDescription) {
  EXPECT_MESSAGE(refusal(NETMC_TEST_FMU_MALFORMED_XML), "modelDescription.xml: malformed XML");
  EXPECT_MESSAGE(refusal(NETMC_TEST_FMU_FMI1_VERSION), "fmiVersion is '1.0': netmc runs FMI 2.0 co-simulation");
  EXPECT_MESSAGE(refusal(NETMC_TEST_FMU_MODEL_EXCHANGE), "model exchange only (no <CoSimulation> element)");
}

TEST(FmuRefusal, TheBinary) {
  const std::string unloadable = refusal(NETMC_TEST_FMU_UNLOADABLE_BINARY);
  EXPECT_MESSAGE(unloadable, "binaries/linux64/seed001_axis.so: cannot load the binary: ");
  EXPECT_MESSAGE(unloadable, "model.so");  // the dynamic loader's own text follows
  EXPECT_MESSAGE(refusal(NETMC_TEST_FMU_NO_DO_STEP), "the binary lacks fmi2DoStep");
}

TEST(FmuRefusal, TheVariablesTheOptionsName) {
  EXPECT_MESSAGE(refusal(kAxis + ":input=nope"), "option 'input=nope': the FMU has no variable 'nope'");
  EXPECT_MESSAGE(refusal(kAxis + ":output=u"), "option 'output=u': variable 'u' has causality input, expected output");
  EXPECT_MESSAGE(refusal(kAxis + ":input=x"), "variable 'x' has causality output, expected input");
  EXPECT_MESSAGE(refusal(kAxis + ":velocity=b"), "option 'velocity=b': variable 'b' has causality parameter");
  EXPECT_MESSAGE(refusal(kAxis + ":x=1"), "option 'x': variable 'x' has causality output and variability continuous, "
                                          "expected a parameter");
  EXPECT_MESSAGE(refusal(kAxis + ":mass=1"), "option 'mass': the FMU has no variable 'mass'");
  EXPECT_MESSAGE(refusal(kAxis + ":mass=1"), "(netmc sim --plant-parameters fmu:");  // where the names are
  EXPECT_MESSAGE(refusal(kAxis + ":position_start=u"), "option 'position_start=u': variable 'u'");
  EXPECT_MESSAGE(refusal(kAxis + ":position_start=u"), "cannot take a start value");
  EXPECT_MESSAGE(refusal(kAxis + ":velocity_start=nope"), "option 'velocity_start=nope': the FMU has no variable");
  EXPECT_MESSAGE(refusal(std::string(NETMC_TEST_FMU_NO_START_VARIABLES) + ":gear=2"),
                 "option 'gear': variable 'gear' is Integer, netmc needs a Real");
  AxisOverrides wrong;
  wrong.parameters = {{"u", 1.0}};
  EXPECT_MESSAGE(refusal(kAxis, {wrong}), "axis 0 parameter 'u': variable 'u' has causality input");
}

TEST(FmuRefusal, TheSet) {
  const auto two_axes = [](const std::string& text, std::vector<AxisOverrides> overrides = {}) {
    return message_of<std::invalid_argument>([&] { make_fmu_plant_set(text, 2, overrides); });
  };
  EXPECT_MESSAGE(two_axes(NETMC_TEST_FMU_ONCE_PER_PROCESS),
                 "the model declares canBeInstantiatedOnlyOncePerProcess: it can run one axis, not 2");
  EXPECT_MESSAGE(two_axes(kAxis + ":2.b=1"), "option '2.b': names axis 2 of a set of 2 axes");
  EXPECT_MESSAGE(two_axes(kAxis + ":w.b=1"), "option 'w.b': the FMU has no variable 'w.b'");
  AxisOverrides disturbed;
  disturbed.disturbance.constant = 0.1;
  EXPECT_MESSAGE(two_axes(kAxis, {AxisOverrides{}, disturbed}),
                 "axis 1: a disturbance is not supported for FMU plants");
  EXPECT_MESSAGE(message_of<std::invalid_argument>([&] { make_fmu_plant_set(kAxis, 0); }),
                 "axis_count must be 1, 2 or 3");
  EXPECT_MESSAGE(message_of<std::invalid_argument>([&] { make_fmu_plant_set(kAxis, 4); }),
                 "axis_count must be 1, 2 or 3");
  EXPECT_MESSAGE(message_of<std::invalid_argument>([&] { make_fmu_plant_set(kAxis, 1, std::vector<AxisOverrides>(2)); }),
                 "2 axis overrides for 1 axes");
  // Axis-qualified parameters reach their axis only.
  AxisSet set = make_fmu_plant_set(kAxis + ":y.b=3,0.b=4,a2=-5", 2);
  EXPECT_NE(set.axes[0]->describe().find("parameters b=4, a2=-5"), std::string::npos) << set.axes[0]->describe();
  EXPECT_NE(set.axes[1]->describe().find("parameters b=3, a2=-5"), std::string::npos) << set.axes[1]->describe();
}

TEST(FmuRefusal, AParameterTheFmuRejectsFailsTheProbe) {
  const std::string message = message_of<std::runtime_error>([&] { fmu_axis(kAxis, ":coulomb=-1"); });
  EXPECT_MESSAGE(message, "fmi2ExitInitializationMode failed at t = 0 s: fmi2Error");
  EXPECT_MESSAGE(message, "the FMU said: coulomb must be >= 0");
}

TEST(FmuRefusal, AResetWithoutAStartVariable) {
  // No x0 / v0: the FMU starts where its own start values put it (0, at rest), and only there.
  auto plant = fmu_axis(NETMC_TEST_FMU_NO_START_VARIABLES, ":velocity=v");
  plant->reset(0.0, 0.0);
  EXPECT_MESSAGE(message_of<std::invalid_argument>([&] { plant->reset(0.01, 0.0); }),
                 "cannot reset to x = 0.01 m: no variable takes the start position (the FMU has no x0; name one "
                 "with position_start=NAME), and the FMU starts at 0 m");
  EXPECT_MESSAGE(message_of<std::invalid_argument>([&] { plant->reset(0.0, 0.2); }),
                 "cannot reset to v = 0.2 m/s: no variable takes the start velocity");
  EXPECT_THROW(plant->reset(std::nan(""), 0.0), std::invalid_argument);
}

TEST(FmuRefusal, AFailingStepThrowsNamingTheTimeAndTheStatus) {
  // The failing FMU refuses any step that would end after 10.5 ms.
  auto plant = fmu_axis(NETMC_TEST_FMU_FAILING, ":velocity=v");
  plant->reset(0.0, 0.0);
  for (int k = 0; k < 10; ++k) plant->advance(1e-3, 1.0);
  const std::string message = message_of<std::runtime_error>([&] { plant->advance(1e-3, 1.0); });
  EXPECT_MESSAGE(message, "failing.fmu: fmi2DoStep (step 0.001 s) failed at t = 0.01 s: fmi2Error");
  EXPECT_MESSAGE(message, "the FMU said: fmi2DoStep: the test model fails by design after t (0.0105)");
  // Broken until reset: no step, no clone; a reset brings it back.
  EXPECT_MESSAGE(message_of<std::runtime_error>([&] { plant->advance(1e-3, 1.0); }), "reset() the plant first");
  EXPECT_THROW(plant->clone(), std::runtime_error);
  plant->reset(0.0, 0.0);
  for (int k = 0; k < 10; ++k) plant->advance(1e-3, 1.0);
  EXPECT_GT(plant->position(), 0.0);
  EXPECT_THROW(plant->advance(1e-3, 1.0), std::runtime_error);
}

TEST(FmuRefusal, ANonFiniteOutputThrows) {
  // a2 = 1e6 1/s: e^(a2 h) overflows within the first 1 ms step.
  auto plant = fmu_axis(kAxis, ":velocity=v,coulomb=0,a2=1e6");
  plant->reset(0.0, 0.0);
  const std::string message = message_of<std::runtime_error>([&] { plant->advance(1e-3, 1.0); });
  EXPECT_MESSAGE(message, "is not finite");
  EXPECT_MESSAGE(message, "at t = 0.001 s");
}

}  // namespace
}  // namespace netmc::plant::fmu
