#pragma once
// The device side of CiA 402's power state machine: what a servo drive does with the
// controlwords its master writes and with its own faults. Transitions are numbered as in the
// standard. A quick stop runs with option code 2 (slow down on the quick stop ramp, then Switch
// on disabled) and a fault reaction slows down on the same ramp before Fault: the drive that
// owns this machine reports the end of either ramp (reaction_complete).

#include <cstdint>

#include "server/drive/cia402.hpp"

namespace netmc::drive {

class PowerStateMachine {
 public:
  // Transitions 0 and 1: Not ready to switch on, then Switch on disabled once initialised.
  PowerStateMachine() = default;
  void initialised();

  // A controlword from the master (transitions 2-12, 15 on the rising edge of bit 7, 16 never:
  // option code 2 does not return from a quick stop).
  void apply(std::uint16_t controlword);
  // The drive detected a fault (13): it reacts on the quick stop ramp and then holds Fault until
  // the master resets it. A fault during a reaction keeps the first error code.
  void fault(std::uint16_t error_code);
  // The quick stop or fault reaction ramp is at standstill (12, 14).
  void reaction_complete();

  PowerState state() const { return state_; }
  // Whether the power stage drives the motor: the states in which the drive's command or one
  // of its ramps acts.
  bool power_on() const;
  std::uint16_t statusword() const { return statusword_bits(state_) | statusword::remote; }
  std::uint16_t error_code() const { return error_code_; }
  std::uint16_t last_controlword() const { return last_controlword_; }

 private:
  PowerState state_ = PowerState::not_ready_to_switch_on;
  std::uint16_t error_code_ = error_code::none;
  std::uint16_t last_controlword_ = 0;
};

}  // namespace netmc::drive
