// CiA 402's power state machine, checked against the standard's tables: the statusword patterns,
// the device's transitions for each controlword, and a master that reaches Operation enabled from
// every state through controlword_towards.
#include <gtest/gtest.h>

#include <vector>

#include "server/drive/cia402.hpp"
#include "server/drive/power_state_machine.hpp"
#include "tests/drive/power_state_printer.hpp"

namespace netmc::drive {
namespace {

const std::vector<PowerState> kStates{PowerState::not_ready_to_switch_on, PowerState::switch_on_disabled,
                                      PowerState::ready_to_switch_on,     PowerState::switched_on,
                                      PowerState::operation_enabled,      PowerState::quick_stop_active,
                                      PowerState::fault_reaction_active,  PowerState::fault};

TEST(Cia402, StatuswordPatternsAreTheStandardsTable) {
  // The standard's table, written out (x = don't care, set to 1 here to show it is ignored).
  EXPECT_EQ(decode_statusword(0b0000'0000), PowerState::not_ready_to_switch_on);
  EXPECT_EQ(decode_statusword(0b1011'0000), PowerState::not_ready_to_switch_on);
  EXPECT_EQ(decode_statusword(0b0100'0000), PowerState::switch_on_disabled);
  EXPECT_EQ(decode_statusword(0b1111'0000), PowerState::switch_on_disabled);
  EXPECT_EQ(decode_statusword(0b0010'0001), PowerState::ready_to_switch_on);
  EXPECT_EQ(decode_statusword(0b0010'0011), PowerState::switched_on);
  EXPECT_EQ(decode_statusword(0b0010'0111), PowerState::operation_enabled);
  EXPECT_EQ(decode_statusword(0b0000'0111), PowerState::quick_stop_active);
  EXPECT_EQ(decode_statusword(0b0000'1111), PowerState::fault_reaction_active);
  EXPECT_EQ(decode_statusword(0b0010'1111), PowerState::fault_reaction_active);
  EXPECT_EQ(decode_statusword(0b0000'1000), PowerState::fault);
  EXPECT_EQ(decode_statusword(0b0011'1000), PowerState::fault);
  EXPECT_FALSE(decode_statusword(0b0010'0101));  // operation enabled without switched on: no state
  for (PowerState state : kStates) {
    EXPECT_EQ(decode_statusword(statusword_bits(state)), state) << power_state_name(state);
    EXPECT_EQ(power_state_from_name(power_state_name(state)), state);
  }
}

TEST(Cia402, ControlwordCommandsDecodeByPriority) {
  EXPECT_EQ(decode_controlword(controlword::shutdown), PowerCommand::shutdown);
  EXPECT_EQ(decode_controlword(controlword::switch_on), PowerCommand::switch_on);
  EXPECT_EQ(decode_controlword(controlword::enable_operation), PowerCommand::enable_operation);
  EXPECT_EQ(decode_controlword(controlword::disable_voltage), PowerCommand::disable_voltage);
  EXPECT_EQ(decode_controlword(controlword::quick_stop), PowerCommand::quick_stop);
  EXPECT_EQ(decode_controlword(0x000D), PowerCommand::disable_voltage);  // bit 1 low wins
  EXPECT_EQ(decode_controlword(0x000B), PowerCommand::quick_stop);       // then bit 2 low
}

TEST(PowerStateMachine, FollowsTheStandardsTransitions) {
  PowerStateMachine drive;
  EXPECT_EQ(drive.state(), PowerState::not_ready_to_switch_on);
  drive.apply(controlword::enable_operation);  // nothing before initialisation
  EXPECT_EQ(drive.state(), PowerState::not_ready_to_switch_on);
  drive.initialised();  // 1
  EXPECT_EQ(drive.state(), PowerState::switch_on_disabled);
  drive.apply(controlword::switch_on);  // not a transition of Switch on disabled
  EXPECT_EQ(drive.state(), PowerState::switch_on_disabled);
  drive.apply(controlword::shutdown);  // 2
  EXPECT_EQ(drive.state(), PowerState::ready_to_switch_on);
  drive.apply(controlword::switch_on);  // 3
  EXPECT_EQ(drive.state(), PowerState::switched_on);
  drive.apply(controlword::enable_operation);  // 4
  EXPECT_EQ(drive.state(), PowerState::operation_enabled);
  EXPECT_TRUE(drive.power_on());
  drive.apply(controlword::switch_on);  // 5 (disable operation)
  EXPECT_EQ(drive.state(), PowerState::switched_on);
  drive.apply(controlword::shutdown);  // 6
  EXPECT_EQ(drive.state(), PowerState::ready_to_switch_on);
  drive.apply(controlword::quick_stop);  // 7
  EXPECT_EQ(drive.state(), PowerState::switch_on_disabled);
  drive.apply(controlword::shutdown);
  drive.apply(controlword::enable_operation);  // 3 + 4 at once
  EXPECT_EQ(drive.state(), PowerState::operation_enabled);
  drive.apply(controlword::shutdown);  // 8
  EXPECT_EQ(drive.state(), PowerState::ready_to_switch_on);
  drive.apply(controlword::enable_operation);
  drive.apply(controlword::disable_voltage);  // 9
  EXPECT_EQ(drive.state(), PowerState::switch_on_disabled);
  drive.apply(controlword::shutdown);
  drive.apply(controlword::switch_on);
  drive.apply(controlword::quick_stop);  // 10
  EXPECT_EQ(drive.state(), PowerState::switch_on_disabled);
  drive.apply(controlword::shutdown);
  drive.apply(controlword::enable_operation);
  drive.apply(controlword::quick_stop);  // 11
  EXPECT_EQ(drive.state(), PowerState::quick_stop_active);
  EXPECT_TRUE(drive.power_on());
  drive.apply(controlword::enable_operation);  // 16 is not taken with option code 2
  EXPECT_EQ(drive.state(), PowerState::quick_stop_active);
  drive.reaction_complete();  // 12 at standstill
  EXPECT_EQ(drive.state(), PowerState::switch_on_disabled);

  drive.apply(controlword::shutdown);
  drive.apply(controlword::enable_operation);
  drive.fault(0x8611);  // 13
  EXPECT_EQ(drive.state(), PowerState::fault_reaction_active);
  drive.fault(0x2310);  // the first error stays
  EXPECT_EQ(drive.error_code(), 0x8611);
  drive.apply(controlword::fault_reset);  // nothing while reacting
  EXPECT_EQ(drive.state(), PowerState::fault_reaction_active);
  drive.reaction_complete();  // 14
  EXPECT_EQ(drive.state(), PowerState::fault);
  EXPECT_FALSE(drive.power_on());
  drive.apply(controlword::fault_reset);  // bit 7 was already high: no rising edge
  EXPECT_EQ(drive.state(), PowerState::fault);
  drive.apply(controlword::disable_voltage);
  drive.apply(controlword::fault_reset);  // 15
  EXPECT_EQ(drive.state(), PowerState::switch_on_disabled);
  EXPECT_EQ(drive.error_code(), 0u);

  PowerStateMachine idle;
  idle.initialised();
  idle.fault(0x8100);  // no power: straight to Fault
  EXPECT_EQ(idle.state(), PowerState::fault);
}

// A master writing controlword_towards and a device taking it meet at every target from every
// state a master can leave, in at most three writes.
TEST(PowerStateMachine, TheMastersNextControlwordReachesEveryTarget) {
  const std::vector<PowerState> targets{PowerState::switch_on_disabled, PowerState::ready_to_switch_on,
                                        PowerState::switched_on, PowerState::operation_enabled};
  const auto reach = [](PowerStateMachine& drive, PowerState target) {
    for (int writes = 0; writes <= 3; ++writes) {
      if (drive.state() == target) return writes;
      const auto word = controlword_towards(drive.state(), target);
      if (!word) return -1;
      drive.apply(*word);
    }
    return drive.state() == target ? 3 : -1;
  };
  for (PowerState start : {PowerState::switch_on_disabled, PowerState::ready_to_switch_on, PowerState::switched_on,
                           PowerState::operation_enabled, PowerState::quick_stop_active}) {
    for (PowerState target : targets) {
      PowerStateMachine drive;
      drive.initialised();
      ASSERT_GE(reach(drive, start == PowerState::quick_stop_active ? PowerState::operation_enabled : start), 0);
      if (start == PowerState::quick_stop_active) drive.apply(controlword::quick_stop);
      ASSERT_EQ(drive.state(), start);
      const int writes = reach(drive, target);
      EXPECT_GE(writes, 0) << power_state_name(start) << " -> " << power_state_name(target);
      EXPECT_LE(writes, 3);
    }
  }
  EXPECT_FALSE(controlword_towards(PowerState::fault, PowerState::operation_enabled));
  EXPECT_FALSE(controlword_towards(PowerState::fault_reaction_active, PowerState::operation_enabled));
}

TEST(Cia402, ErrorCodesAreNamed) {
  EXPECT_EQ(describe_error_code(0x8100), "0x8100 (communication)");
  EXPECT_EQ(describe_error_code(0x2310), "0x2310 (current)");
  EXPECT_EQ(describe_error_code(0x1234), "0x1234");
}

}  // namespace
}  // namespace netmc::drive
