#include "server/drive/cia402.hpp"

#include <fmt/format.h>

#include <array>
#include <utility>

namespace netmc::drive {
namespace {

constexpr std::array<std::pair<PowerState, const char*>, 8> kNames{{
    {PowerState::not_ready_to_switch_on, "Not ready to switch on"},
    {PowerState::switch_on_disabled, "Switch on disabled"},
    {PowerState::ready_to_switch_on, "Ready to switch on"},
    {PowerState::switched_on, "Switched on"},
    {PowerState::operation_enabled, "Operation enabled"},
    {PowerState::quick_stop_active, "Quick stop active"},
    {PowerState::fault_reaction_active, "Fault reaction active"},
    {PowerState::fault, "Fault"},
}};

}  // namespace

const char* power_state_name(PowerState state) {
  for (const auto& [candidate, name] : kNames) {
    if (candidate == state) return name;
  }
  return "?";
}

std::optional<PowerState> power_state_from_name(const std::string& name) {
  for (const auto& [state, candidate] : kNames) {
    if (name == candidate) return state;
  }
  return std::nullopt;
}

// Bit 1 (enable voltage) low wins over everything, then bit 2 (quick stop, active low), then
// bits 0 and 3.
PowerCommand decode_controlword(std::uint16_t word) {
  if ((word & 0x02) == 0) return PowerCommand::disable_voltage;
  if ((word & 0x04) == 0) return PowerCommand::quick_stop;
  if ((word & 0x01) == 0) return PowerCommand::shutdown;
  if ((word & 0x08) == 0) return PowerCommand::switch_on;
  return PowerCommand::enable_operation;
}

std::optional<std::uint16_t> controlword_towards(PowerState from, PowerState target) {
  if (from == target) return std::nullopt;
  switch (from) {
    case PowerState::not_ready_to_switch_on:
    case PowerState::fault_reaction_active:
    case PowerState::fault:
      return std::nullopt;
    case PowerState::quick_stop_active:
      // Option code 2 ends a quick stop in Switch on disabled by itself; disable voltage gets
      // there at once (transition 12).
      return controlword::disable_voltage;
    case PowerState::switch_on_disabled:
      return controlword::shutdown;  // 2: every target is beyond Ready to switch on
    case PowerState::ready_to_switch_on:
      if (target == PowerState::switch_on_disabled) return controlword::disable_voltage;  // 7
      return target == PowerState::operation_enabled ? controlword::enable_operation  // 3 + 4
                                                     : controlword::switch_on;        // 3
    case PowerState::switched_on:
      if (target == PowerState::switch_on_disabled) return controlword::disable_voltage;  // 10
      if (target == PowerState::ready_to_switch_on) return controlword::shutdown;         // 6
      return controlword::enable_operation;                                               // 4
    case PowerState::operation_enabled:
      if (target == PowerState::switch_on_disabled) return controlword::disable_voltage;  // 9
      if (target == PowerState::ready_to_switch_on) return controlword::shutdown;         // 8
      return controlword::switch_on;                                                      // 5
  }
  return std::nullopt;
}

std::string describe_error_code(std::uint16_t code) {
  const char* what = nullptr;
  switch (code) {
    case error_code::none: what = "no error"; break;
    case error_code::communication: what = "communication"; break;
    case error_code::following_error: what = "following error"; break;
    case error_code::position_limit: what = "software position limit"; break;
    case error_code::velocity_limit: what = "velocity limit"; break;
    case error_code::plant_not_finite: what = "model state not finite"; break;
    default:
      // The IEC 61800-7-301 classes by the high nibble.
      switch (code >> 12) {
        case 0x2: what = "current"; break;
        case 0x3: what = "voltage"; break;
        case 0x4: what = "temperature"; break;
        case 0x5: what = "device hardware"; break;
        case 0x6: what = "device software"; break;
        case 0x7: what = "additional modules"; break;
        case 0x8: what = "monitoring"; break;
        case 0x9: what = "external error"; break;
        case 0xF: what = "device specific"; break;
        default: break;
      }
  }
  return what ? fmt::format("0x{:04X} ({})", code, what) : fmt::format("0x{:04X}", code);
}

}  // namespace netmc::drive
