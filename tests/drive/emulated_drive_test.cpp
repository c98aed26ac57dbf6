// The drive netmc's simulations run: its probe of the plant, its modes and its ramps, each against
// a closed form of the linear speed-mode servo x'' = -20 x' + 20 u.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "plant/second_order_axis.hpp"
#include "server/drive/emulated_drive.hpp"
#include "tests/drive/power_state_printer.hpp"
#include "tests/drive/linear_servo_plant.hpp"

namespace netmc::drive {
namespace {


EmulatedDrive enabled_drive(EmulatedDriveSettings settings = {}) {
  EmulatedDrive drive(linear_servo_plant(), settings);
  drive.power_up();
  drive.restart_at(0.0);
  drive.apply_controlword(controlword::shutdown);
  drive.apply_controlword(controlword::enable_operation);
  return drive;
}

TEST(EmulatedDrive, ProbesTheInputGainOfItsPlant) {
  // From rest, u = U for T = 2 ms: v = (b U / 20)(1 - e^{-20 T}), so the probe reads
  // b (1 - e^{-20 T}) / (20 T).
  const EmulatedDrive drive(linear_servo_plant(), {});
  EXPECT_NEAR(drive.input_gain(), 20.0 * (1.0 - std::exp(-0.04)) / 0.04, 1e-9);
}

TEST(EmulatedDrive, CstHoldsTheTargetAsThePlantsInputFromTheInstantItIsWritten) {
  EmulatedDrive drive = enabled_drive();
  drive.advance_to(0.0012);
  drive.set_target(OperationMode::cst, 1.0);
  drive.advance_to(0.005);
  // Paper 001, eq. 4: v = b/a2 (e^{a2 (h - tau)} - 1) with a2 = -20, b = 20.
  EXPECT_NEAR(drive.velocity(), -(std::exp(-20.0 * (0.005 - 0.0012)) - 1.0), 1e-12);
  EXPECT_EQ(drive.statusword() & 0x6F, 0x27);
  // Not powered: the target does not act.
  EmulatedDrive idle(linear_servo_plant(), {});
  idle.power_up();
  idle.set_target(OperationMode::cst, 1.0);
  idle.advance_to(0.01);
  EXPECT_EQ(idle.velocity(), 0.0);
}

TEST(EmulatedDrive, CsvAndCspReachTheirTargets) {
  EmulatedDrive drive = enabled_drive();
  drive.set_mode(OperationMode::csv);
  drive.set_target(OperationMode::csv, 0.05);
  drive.advance_to(0.2);  // 40 Hz loop: settled well within 0.2 s
  EXPECT_NEAR(drive.velocity(), 0.05, 1e-4);
  drive.set_mode(OperationMode::csp);
  drive.set_target(OperationMode::csp, 0.02);
  drive.advance_to(1.0);
  EXPECT_NEAR(drive.position(), 0.02, 1e-6);
  EXPECT_TRUE(drive.statusword() & statusword::target_reached);
}

TEST(EmulatedDrive, EnablingHoldsWhereTheAxisStands) {
  EmulatedDrive drive(linear_servo_plant(), {});
  drive.power_up();
  drive.restart_at(0.03);
  drive.set_mode(OperationMode::csp);
  drive.set_target(OperationMode::csp, 0.5);  // stale, written before enabling
  drive.apply_controlword(controlword::shutdown);
  drive.apply_controlword(controlword::enable_operation);
  drive.advance_to(0.5);
  EXPECT_NEAR(drive.position(), 0.03, 1e-9);
}

TEST(EmulatedDrive, AFaultRampsDownThenHoldsFaultUntilReset) {
  EmulatedDriveSettings settings;
  settings.quick_stop_deceleration_m_s2 = 2.0;
  EmulatedDrive drive = enabled_drive(settings);
  drive.set_target(OperationMode::cst, 0.4);
  drive.advance_to(0.5);  // v -> 0.4 m/s
  const double x0 = drive.position(), v0 = drive.velocity();
  drive.raise_fault(error_code::communication);
  EXPECT_EQ(drive.state(), PowerState::fault_reaction_active);
  drive.advance_to(0.5 + 0.25);
  EXPECT_EQ(drive.state(), PowerState::fault);
  EXPECT_NEAR(drive.position() - x0, v0 * v0 / 4.0, 0.003);  // v^2 / 2a
  EXPECT_EQ(drive.statusword() & 0x4F, 0x08);
  EXPECT_EQ(drive.error_code(), error_code::communication);
  drive.apply_controlword(controlword::fault_reset);
  EXPECT_EQ(drive.state(), PowerState::switch_on_disabled);
}

TEST(EmulatedDrive, APlantWithoutInputIsRefused) {
  plant::SecondOrderAxisParameters p;
  p.b = 0.0;
  EXPECT_THROW(EmulatedDrive(std::make_unique<plant::SecondOrderAxis>(p), {}), std::invalid_argument);
  EmulatedDriveSettings bad;
  bad.cycle_s = 0.0;
  EXPECT_THROW(EmulatedDrive(linear_servo_plant(), bad), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::drive
