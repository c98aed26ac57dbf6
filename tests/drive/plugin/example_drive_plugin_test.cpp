// The example drive plugin (examples/drive_plugin) through PluginDrive, in real time: its
// configuration and refusals, the modes it lists, a run-time failure as a DriveError, the CiA 402
// sequence to Operation enabled, CST motion as the closed form of x'' = -20 x' + 20 u says,
// a CSP target reached, a quick stop to Switch on disabled, and a watchdog fault with its reset.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "server/drive/cia402.hpp"
#include "server/drive/plugin/plugin_drive.hpp"

namespace netmc::drive {
namespace {

using Clock = std::chrono::steady_clock;  // CLOCK_MONOTONIC, the plugin's clock

double seconds(Clock::duration duration) { return std::chrono::duration<double>(duration).count(); }

std::unique_ptr<PluginDrive> example(const std::string& settings = "") {
  return PluginDrive::load(std::string(NETMC_TEST_PLUGIN_EXAMPLE) + (settings.empty() ? "" : ":" + settings));
}

std::string state_name(Drive& drive) {
  const auto state = decode_statusword(drive.read().statusword);
  return state ? power_state_name(*state) : "no CiA 402 state";
}

// Controlwords towards Operation enabled, one state at a time, as a master sends them.
void enable(Drive& drive) {
  for (const PowerState target :
       {PowerState::ready_to_switch_on, PowerState::switched_on, PowerState::operation_enabled}) {
    const auto from = decode_statusword(drive.read().statusword);
    ASSERT_TRUE(from);
    const auto word = controlword_towards(*from, target);
    ASSERT_TRUE(word) << power_state_name(*from) << " towards " << power_state_name(target);
    drive.write_controlword(*word);
    ASSERT_EQ(state_name(drive), power_state_name(target));
  }
}

// Reads until `done` holds or `timeout_s` passes; the last reading.
template <typename Done>
DriveFeedback poll_until(Drive& drive, Done done, double timeout_s) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  DriveFeedback feedback = drive.read();
  while (!done(feedback) && Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    drive.cycle(0.0);
    feedback = drive.read();
  }
  return feedback;
}

bool in_state(const DriveFeedback& feedback, PowerState state) {
  return decode_statusword(feedback.statusword) == state;
}

TEST(ExampleDrivePlugin, DescribesItselfAndListsCstAndCsp) {
  auto drive = example();
  EXPECT_EQ(drive->describe(), std::string("plugin:") + NETMC_TEST_PLUGIN_EXAMPLE +
                                   " (example drive: x'' = -20 x' + 20 u in real time, CST and CSP)");
  EXPECT_EQ(drive->job_mode(), OperationMode::cst);
  EXPECT_TRUE(drive->supports(OperationMode::cst));
  EXPECT_TRUE(drive->supports(OperationMode::csp));
  EXPECT_FALSE(drive->supports(OperationMode::csv));
  EXPECT_FALSE(drive->virtual_time());
  drive->open();
  try {
    drive->write_mode(OperationMode::csv);
    FAIL() << "CSV written";
  } catch (const DriveError& error) {
    EXPECT_EQ(std::string(error.what()), std::string("plugin ") + NETMC_TEST_PLUGIN_EXAMPLE +
                                             ": write_mode in csv: the plugin supports csp, cst only");
  }
}

TEST(ExampleDrivePlugin, ItsCreateRefusesUnknownKeysAndBadValuesInItsOwnWords) {
  const std::string prefix = std::string("plugin ") + NETMC_TEST_PLUGIN_EXAMPLE + ": refused its configuration: ";
  try {
    example("a2=-10,speed=3");
    FAIL() << "loaded";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), prefix + "unknown key 'speed' (keys: a2, b, position, watchdog)");
  }
  try {
    example("b=-1");
    FAIL() << "loaded";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), prefix + "b=-1 is outside [1e-09, 1e+09]");
  }
}

TEST(ExampleDrivePlugin, AFailureAtRunTimeIsADriveErrorWithThePluginsText) {
  auto drive = example();
  try {
    drive->write_controlword(controlword::shutdown);  // before open
    FAIL() << "written";
  } catch (const DriveError& error) {
    EXPECT_EQ(std::string(error.what()),
              std::string("plugin ") + NETMC_TEST_PLUGIN_EXAMPLE + ": write_controlword: the drive is not open");
  }
}

// From rest at 10 mm, u = 1 from the write on: x(t) = x0 + t - (1 - e^{-20 t}) / 20 and
// v(t) = 1 - e^{-20 t}. Both rise with t, so the plugin's reading lies between the closed form
// at the shortest and the longest time the calls allow, however the test was scheduled.
TEST(ExampleDrivePlugin, GoesToOperationEnabledMovesInCstReachesACspTargetAndQuickStops) {
  const double x0 = 0.01;
  auto drive = example("position=0.01");
  drive->open();
  EXPECT_EQ(state_name(*drive), "Switch on disabled");
  drive->write_mode(OperationMode::cst);
  enable(*drive);
  if (HasFatalFailure()) return;
  EXPECT_EQ(drive->read().position_m, x0);

  const auto x = [x0](double t) { return x0 + t - (1.0 - std::exp(-20.0 * t)) / 20.0; };
  const auto v = [](double t) { return 1.0 - std::exp(-20.0 * t); };
  const auto write_begin = Clock::now();
  drive->write_target(OperationMode::cst, 1.0);
  const auto write_end = Clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto read_begin = Clock::now();
  const DriveFeedback moving = drive->read();
  const auto read_end = Clock::now();
  const double shortest = seconds(read_begin - write_end), longest = seconds(read_end - write_begin);
  EXPECT_TRUE(moving.has_velocity);
  EXPECT_GE(moving.position_m, x(shortest) - 1e-12);
  EXPECT_LE(moving.position_m, x(longest) + 1e-12);
  EXPECT_GE(moving.velocity_m_s, v(shortest) - 1e-12);
  EXPECT_LE(moving.velocity_m_s, v(longest) + 1e-12);
  EXPECT_TRUE(moving.statusword & statusword::target_reached);  // CST: always

  // CSP: the drive's position loop holds where the axis was, then takes it to 50 mm.
  drive->write_mode(OperationMode::csp);
  drive->write_target(OperationMode::csp, 0.05);
  const DriveFeedback reached = poll_until(
      *drive,
      [](const DriveFeedback& f) {
        return (f.statusword & statusword::target_reached) && std::abs(f.velocity_m_s) < 1e-4;
      },
      5.0);
  EXPECT_NEAR(reached.position_m, 0.05, 1e-6);
  EXPECT_LT(std::abs(reached.velocity_m_s), 1e-4);
  EXPECT_EQ(decode_statusword(reached.statusword), PowerState::operation_enabled);

  // Back to CST at u = 0.5 (just under 0.5 m/s once settled), then a quick stop at 2.5 m/s^2:
  // v^2 / 2a = 50 mm and 0.2 s to standstill, then Switch on disabled (option code 2). The axis
  // also runs on at most 0.5 m/s between the reading before and the quick stop's write.
  drive->write_mode(OperationMode::cst);
  drive->write_target(OperationMode::cst, 0.5);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  drive->write_quick_stop_deceleration(2.5);
  const auto read_before = Clock::now();
  const DriveFeedback before = drive->read();
  EXPECT_NEAR(before.velocity_m_s, 0.5, 0.01);
  drive->write_controlword(controlword::quick_stop);
  const double run_on_m = 0.5 * seconds(Clock::now() - read_before);
  EXPECT_EQ(state_name(*drive), "Quick stop active");
  const DriveFeedback stopped = poll_until(
      *drive, [](const DriveFeedback& f) { return in_state(f, PowerState::switch_on_disabled); }, 3.0);
  EXPECT_EQ(decode_statusword(stopped.statusword), PowerState::switch_on_disabled);
  EXPECT_LT(std::abs(stopped.velocity_m_s), 1e-3);
  const double distance = stopped.position_m - before.position_m;
  EXPECT_GT(distance, 0.8 * 0.05) << distance;
  EXPECT_LT(distance, 1.2 * 0.05 + run_on_m) << distance;
  drive->close();
}

// The master silent for longer than the watchdog while enabled: a fault reaction (at rest, over
// at once) and Fault with 0x8100, which only bit 7's rising edge clears.
TEST(ExampleDrivePlugin, AWatchdogFaultHoldsUntilAFaultResetEdge) {
  auto drive = example("watchdog=0.25");
  drive->open();
  enable(*drive);
  if (HasFatalFailure()) return;
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const DriveFeedback faulted = drive->read();
  EXPECT_EQ(decode_statusword(faulted.statusword), PowerState::fault);
  EXPECT_EQ(faulted.error_code, error_code::communication);
  EXPECT_FALSE(controlword_towards(PowerState::fault, PowerState::operation_enabled));
  drive->write_controlword(controlword::enable_operation);  // no reset: Fault stays
  EXPECT_EQ(state_name(*drive), "Fault");
  drive->write_controlword(controlword::fault_reset);  // bit 7 rises
  const DriveFeedback reset = drive->read();
  EXPECT_EQ(decode_statusword(reset.statusword), PowerState::switch_on_disabled);
  EXPECT_EQ(reset.error_code, error_code::none);
  enable(*drive);
}

}  // namespace
}  // namespace netmc::drive
