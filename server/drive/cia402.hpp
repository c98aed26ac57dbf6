#pragma once
// The CiA 402 drive profile's power state machine as the standard defines it (IEC 61800-7-201,
// CiA 402 part 2, "PDS finite state automaton"): the states, how the statusword (object 0x6041)
// encodes them, the controlword (0x6040) commands that move between them, and the next command
// a master sends to reach a state. Every servo vendor implements this machine; netmc's axis node
// drives it as a master, and the simulated and emulated drives implement it as a device.

#include <cstdint>
#include <optional>
#include <string>

namespace netmc::drive {

enum class PowerState : std::uint8_t {
  not_ready_to_switch_on,
  switch_on_disabled,
  ready_to_switch_on,
  switched_on,
  operation_enabled,
  quick_stop_active,
  fault_reaction_active,
  fault,
};

// "Operation enabled", as the standard names the state.
const char* power_state_name(PowerState state);
// The inverse of power_state_name; nullopt for any other text.
std::optional<PowerState> power_state_from_name(const std::string& name);

// Statusword bits (0x6041).
namespace statusword {
inline constexpr std::uint16_t ready_to_switch_on = 1u << 0;
inline constexpr std::uint16_t switched_on = 1u << 1;
inline constexpr std::uint16_t operation_enabled = 1u << 2;
inline constexpr std::uint16_t fault = 1u << 3;
inline constexpr std::uint16_t voltage_enabled = 1u << 4;
inline constexpr std::uint16_t quick_stop = 1u << 5;  // 0: a quick stop is active
inline constexpr std::uint16_t switch_on_disabled = 1u << 6;
inline constexpr std::uint16_t warning = 1u << 7;
inline constexpr std::uint16_t remote = 1u << 9;
inline constexpr std::uint16_t target_reached = 1u << 10;
inline constexpr std::uint16_t internal_limit_active = 1u << 11;
}  // namespace statusword

// The state a statusword shows (its bits 0-3, 5 and 6, by the standard's table).
// A pattern the table does not list (a drive that answers nonsense) decodes as nullopt.
// (Inline: a node decodes every sample's statusword.)
constexpr std::optional<PowerState> decode_statusword(std::uint16_t word) {
  if ((word & 0x4F) == 0x00) return PowerState::not_ready_to_switch_on;
  if ((word & 0x4F) == 0x40) return PowerState::switch_on_disabled;
  if ((word & 0x6F) == 0x21) return PowerState::ready_to_switch_on;
  if ((word & 0x6F) == 0x23) return PowerState::switched_on;
  if ((word & 0x6F) == 0x27) return PowerState::operation_enabled;
  if ((word & 0x6F) == 0x07) return PowerState::quick_stop_active;
  if ((word & 0x4F) == 0x0F) return PowerState::fault_reaction_active;
  if ((word & 0x4F) == 0x08) return PowerState::fault;
  return std::nullopt;
}
// The state bits of `state` (voltage enabled where the power stage is on), for a device.
constexpr std::uint16_t statusword_bits(PowerState state) {
  using namespace statusword;
  switch (state) {
    case PowerState::not_ready_to_switch_on: return 0;
    case PowerState::switch_on_disabled: return switch_on_disabled;
    case PowerState::ready_to_switch_on: return quick_stop | voltage_enabled | ready_to_switch_on;
    case PowerState::switched_on: return quick_stop | voltage_enabled | ready_to_switch_on | switched_on;
    case PowerState::operation_enabled:
      return quick_stop | voltage_enabled | ready_to_switch_on | switched_on | operation_enabled;
    case PowerState::quick_stop_active: return voltage_enabled | ready_to_switch_on | switched_on | operation_enabled;
    case PowerState::fault_reaction_active:
      return voltage_enabled | fault | ready_to_switch_on | switched_on | operation_enabled;
    case PowerState::fault: return fault;
  }
  return 0;
}

// Controlword commands (0x6040), as the standard writes them.
namespace controlword {
inline constexpr std::uint16_t shutdown = 0x0006;           // transitions 2, 6, 8
inline constexpr std::uint16_t switch_on = 0x0007;          // 3 (and "disable operation", 5)
inline constexpr std::uint16_t enable_operation = 0x000F;   // 4 (and 3 + 4 from Ready to switch on)
inline constexpr std::uint16_t disable_voltage = 0x0000;    // 7, 9, 10, 12
inline constexpr std::uint16_t quick_stop = 0x0002;         // 7, 10, 11
inline constexpr std::uint16_t fault_reset = 0x0080;        // 15, on the rising edge of bit 7
}  // namespace controlword

// What a controlword commands (bit 7's edge is the device's to see, not decoded here).
enum class PowerCommand : std::uint8_t { disable_voltage, quick_stop, shutdown, switch_on, enable_operation };
PowerCommand decode_controlword(std::uint16_t word);

// The controlword a master writes next to bring a drive from `from` towards `target`, where
// `target` is one of switch_on_disabled, ready_to_switch_on, switched_on or operation_enabled;
// nullopt when it is there, or when only the device can move on (Not ready to switch on, Fault
// reaction active) or only a fault reset can (Fault: see controlword::fault_reset).
std::optional<std::uint16_t> controlword_towards(PowerState from, PowerState target);

// "0x5441"-style text of an error code (0x603F) with its CiA 402 / IEC 61800 class where known:
// "0x8611 (following error)".
std::string describe_error_code(std::uint16_t code);

// Error codes netmc's own devices raise (CiA 402's "device-specific" range FFxx for what the
// standard has no code for).
namespace error_code {
inline constexpr std::uint16_t none = 0x0000;
inline constexpr std::uint16_t communication = 0x8100;       // fieldbus watchdog: the master fell silent
inline constexpr std::uint16_t following_error = 0x8611;
inline constexpr std::uint16_t position_limit = 0x8612;      // software position limit
inline constexpr std::uint16_t velocity_limit = 0x8400;      // velocity speed control
inline constexpr std::uint16_t plant_not_finite = 0xFF01;    // the model's state is no longer finite
}  // namespace error_code

}  // namespace netmc::drive
