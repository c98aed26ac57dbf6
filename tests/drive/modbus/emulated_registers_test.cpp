// The emulator's holding registers over its drive: what a read gives, what a write does, and the
// Modbus exception for each request a drive refuses.
#include <gtest/gtest.h>

#include <array>
#include <memory>

#include "plant/second_order_axis.hpp"
#include "server/drive/emulated_drive.hpp"
#include "server/drive/emulator/emulated_registers.hpp"
#include "server/drive/modbus/modbus_map.hpp"
#include "tests/drive/power_state_printer.hpp"
#include "tests/drive/linear_servo_plant.hpp"

namespace netmc::drive::emulator {
namespace {

using modbus::DriveObject;


// A drive at rest at 0.1 m, initialised, with the default map's registers over it.
EmulatedDrive ready_drive() {
  EmulatedDrive drive(linear_servo_plant(), {});
  drive.restart_at(0.1);
  drive.power_up();
  return drive;
}

struct Bench {
  modbus::ModbusMap map = modbus::default_modbus_map();
  EmulatedDrive drive = ready_drive();
  EmulatedRegisters registers{map, drive};

  RegisterAccess write(std::uint16_t address, std::initializer_list<std::uint16_t> words) {
    const std::vector<std::uint16_t> data(words);
    return registers.write(address, data.data(), static_cast<std::uint16_t>(data.size()));
  }
};

TEST(EmulatedRegisters, AReadGivesTheDrivesStateAndActualValues) {
  Bench bench;
  std::array<std::uint16_t, 9> words{};
  ASSERT_TRUE(bench.registers.read(0, 9, words.data()).ok());
  EXPECT_EQ(words[0], bench.drive.statusword());
  EXPECT_EQ(words[1], 10);  // CST
  EXPECT_EQ(words[2], 0);
  EXPECT_NEAR(bench.map.from_words(DriveObject::position_actual, &words[3]), 0.1, 1e-9);
  // The master's own objects read back as written; a target position starts where the axis is.
  std::array<std::uint16_t, 2> target{};
  ASSERT_TRUE(bench.registers.read(18, 2, target.data()).ok());
  EXPECT_NEAR(bench.map.from_words(DriveObject::target_position, target.data()), 0.1, 1e-9);
  // Half of a 32-bit object may be read.
  EXPECT_TRUE(bench.registers.read(4, 1, words.data()).ok());
}

TEST(EmulatedRegisters, WritesReachTheDriveThroughItsStateMachine) {
  Bench bench;
  ASSERT_TRUE(bench.write(16, {controlword::shutdown}).ok());
  EXPECT_EQ(bench.drive.state(), PowerState::ready_to_switch_on);
  // Controlword and mode in one request (registers 16-17), applied in address order.
  ASSERT_TRUE(bench.write(16, {controlword::enable_operation, 9}).ok());
  EXPECT_EQ(bench.drive.state(), PowerState::operation_enabled);
  EXPECT_EQ(bench.drive.mode(), OperationMode::csv);
  std::array<std::uint16_t, 2> words{};
  bench.map.to_words(DriveObject::target_torque, 0.5, words);
  ASSERT_TRUE(bench.write(22, {words[0], words[1]}).ok());
  ASSERT_TRUE(bench.write(17, {10}).ok());
  bench.drive.advance_to(0.01);
  EXPECT_DOUBLE_EQ(bench.drive.input(), 0.5);
  std::array<std::uint16_t, 1> mode{};
  ASSERT_TRUE(bench.registers.read(17, 1, mode.data()).ok());
  EXPECT_EQ(mode[0], 10);
}

TEST(EmulatedRegisters, RegistersOutsideTheMapAreAnIllegalDataAddress) {
  Bench bench;
  std::array<std::uint16_t, 16> words{};
  const RegisterAccess gap = bench.registers.read(0, 10, words.data());  // register 9 is in no object
  EXPECT_EQ(gap.exception, 2);
  EXPECT_EQ(gap.why, "register 9 is not in the map");
  EXPECT_EQ(bench.registers.read(1000, 1, words.data()).exception, 2);
  EXPECT_EQ(bench.write(30, {1}).exception, 2);
}

TEST(EmulatedRegisters, TheDrivesObjectsAndPartsOfObjectsCannotBeWritten) {
  Bench bench;
  const RegisterAccess statusword = bench.write(0, {0x27});
  EXPECT_EQ(statusword.exception, 2);
  EXPECT_EQ(statusword.why, "statusword (register 0) is read-only");
  EXPECT_EQ(bench.write(18, {1}).why, "a write of target_position (registers 18-19) must cover all of it");
  EXPECT_EQ(bench.write(19, {1}).exception, 2);
  EXPECT_EQ(bench.write(17, {10, 0}).exception, 2);  // the mode, then half a target position
}

TEST(EmulatedRegisters, ValuesTheDriveCannotTakeAreAnIllegalDataValueAndChangeNothing) {
  Bench bench;
  const RegisterAccess mode = bench.write(16, {controlword::shutdown, 7});
  EXPECT_EQ(mode.exception, 3);
  EXPECT_EQ(mode.why, "modes_of_operation: 7 is no mode this drive runs (8 csp, 9 csv, 10 cst)");
  EXPECT_EQ(bench.drive.state(), PowerState::switch_on_disabled);  // the controlword before it did not act
  EXPECT_EQ(bench.write(24, {0, 0}).exception, 3);                  // quick stop deceleration 0
}

TEST(EmulatedRegisters, AnActualValueTheMapCannotHoldIsAServerDeviceFailure) {
  Bench bench;
  bench.drive.restart_at(3.0);  // beyond an int32 of nanometres
  std::array<std::uint16_t, 9> words{};
  const RegisterAccess access = bench.registers.read(0, 9, words.data());
  EXPECT_EQ(access.exception, 4);
  EXPECT_EQ(access.why, "position_actual: 3 m does not fit int32 at 1e+09 counts per metre (range -2.14748 to 2.14748 m)");
}

}  // namespace
}  // namespace netmc::drive::emulator
