#include "server/drive/power_state_machine.hpp"

namespace netmc::drive {

void PowerStateMachine::initialised() {
  if (state_ == PowerState::not_ready_to_switch_on) state_ = PowerState::switch_on_disabled;  // 1
}

void PowerStateMachine::apply(std::uint16_t word) {
  const bool reset_edge = (word & controlword::fault_reset) && !(last_controlword_ & controlword::fault_reset);
  last_controlword_ = word;
  if (state_ == PowerState::fault) {
    if (reset_edge) {
      state_ = PowerState::switch_on_disabled;  // 15
      error_code_ = error_code::none;
    }
    return;
  }
  if (state_ == PowerState::not_ready_to_switch_on || state_ == PowerState::fault_reaction_active) return;
  const PowerCommand command = decode_controlword(word);
  switch (state_) {
    case PowerState::switch_on_disabled:
      if (command == PowerCommand::shutdown) state_ = PowerState::ready_to_switch_on;  // 2
      break;
    case PowerState::ready_to_switch_on:
      if (command == PowerCommand::switch_on) state_ = PowerState::switched_on;  // 3
      if (command == PowerCommand::enable_operation) state_ = PowerState::operation_enabled;  // 3 + 4
      if (command == PowerCommand::disable_voltage || command == PowerCommand::quick_stop) {
        state_ = PowerState::switch_on_disabled;  // 7
      }
      break;
    case PowerState::switched_on:
      if (command == PowerCommand::enable_operation) state_ = PowerState::operation_enabled;  // 4
      if (command == PowerCommand::shutdown) state_ = PowerState::ready_to_switch_on;        // 6
      if (command == PowerCommand::disable_voltage || command == PowerCommand::quick_stop) {
        state_ = PowerState::switch_on_disabled;  // 10
      }
      break;
    case PowerState::operation_enabled:
      if (command == PowerCommand::switch_on) state_ = PowerState::switched_on;              // 5
      if (command == PowerCommand::shutdown) state_ = PowerState::ready_to_switch_on;        // 8
      if (command == PowerCommand::disable_voltage) state_ = PowerState::switch_on_disabled;  // 9
      if (command == PowerCommand::quick_stop) state_ = PowerState::quick_stop_active;       // 11
      break;
    case PowerState::quick_stop_active:
      if (command == PowerCommand::disable_voltage) state_ = PowerState::switch_on_disabled;  // 12
      break;
    case PowerState::not_ready_to_switch_on:
    case PowerState::fault_reaction_active:
    case PowerState::fault:
      break;
  }
}

void PowerStateMachine::fault(std::uint16_t code) {
  if (state_ == PowerState::fault_reaction_active || state_ == PowerState::fault) return;
  error_code_ = code;
  // 13; a drive whose power stage is off has nothing to slow down.
  state_ = power_on() ? PowerState::fault_reaction_active : PowerState::fault;
}

void PowerStateMachine::reaction_complete() {
  if (state_ == PowerState::quick_stop_active) state_ = PowerState::switch_on_disabled;  // 12
  if (state_ == PowerState::fault_reaction_active) state_ = PowerState::fault;           // 14
}

bool PowerStateMachine::power_on() const {
  return state_ == PowerState::operation_enabled || state_ == PowerState::quick_stop_active ||
         state_ == PowerState::fault_reaction_active;
}

}  // namespace netmc::drive
