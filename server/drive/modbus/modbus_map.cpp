#include "server/drive/modbus/modbus_map.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace netmc::drive::modbus {
namespace {

constexpr std::array<DriveObjectInfo, kDriveObjectCount> kObjects{{
    {DriveObject::controlword, "controlword", 0x6040, true, true, nullptr, ""},
    {DriveObject::statusword, "statusword", 0x6041, true, false, nullptr, ""},
    {DriveObject::modes_of_operation, "modes_of_operation", 0x6060, true, true, nullptr, ""},
    {DriveObject::modes_of_operation_display, "modes_of_operation_display", 0x6061, true, false, nullptr, ""},
    {DriveObject::target_position, "target_position", 0x607A, true, true, "counts per metre", "m"},
    {DriveObject::target_velocity, "target_velocity", 0x60FF, true, true, "drive units per m/s", "m/s"},
    {DriveObject::target_torque, "target_torque", 0x6071, true, true, "drive units per unit of the plant's input", ""},
    {DriveObject::position_actual, "position_actual", 0x6064, true, false, "counts per metre", "m"},
    {DriveObject::velocity_actual, "velocity_actual", 0x606C, false, false, "drive units per m/s", "m/s"},
    {DriveObject::torque_actual, "torque_actual", 0x6077, false, false, "drive units per unit of the plant's input", ""},
    {DriveObject::error_code, "error_code", 0x603F, true, false, nullptr, ""},
    {DriveObject::quick_stop_deceleration, "quick_stop_deceleration", 0x6085, false, true, "drive units per m/s^2", "m/s^2"},
}};

struct Range {
  double min;
  double max;
};

Range type_range(RegisterType type) {
  switch (type) {
    case RegisterType::uint16: return {0.0, 65535.0};
    case RegisterType::int16: return {-32768.0, 32767.0};
    case RegisterType::uint32: return {0.0, 4294967295.0};
    case RegisterType::int32: return {-2147483648.0, 2147483647.0};
  }
  return {0.0, 0.0};
}

bool is_word(DriveObject object) {
  return object == DriveObject::controlword || object == DriveObject::statusword || object == DriveObject::error_code;
}

bool is_mode(DriveObject object) {
  return object == DriveObject::modes_of_operation || object == DriveObject::modes_of_operation_display;
}

std::string registers_text(const RegisterPlacement& placement) {
  if (placement.count() == 1) return fmt::format("register {}", placement.address);
  return fmt::format("registers {}-{}", placement.address, placement.address + placement.count() - 1);
}

}  // namespace

const char* register_type_name(RegisterType type) {
  switch (type) {
    case RegisterType::uint16: return "uint16";
    case RegisterType::int16: return "int16";
    case RegisterType::uint32: return "uint32";
    case RegisterType::int32: return "int32";
  }
  return "?";
}

std::optional<RegisterType> register_type_from_name(const std::string& name) {
  for (const RegisterType type : {RegisterType::uint16, RegisterType::int16, RegisterType::uint32, RegisterType::int32}) {
    if (name == register_type_name(type)) return type;
  }
  return std::nullopt;
}

std::uint16_t register_count(RegisterType type) {
  return type == RegisterType::uint32 || type == RegisterType::int32 ? 2 : 1;
}

const DriveObjectInfo& object_info(DriveObject object) { return kObjects[static_cast<std::size_t>(object)]; }

const std::array<DriveObjectInfo, kDriveObjectCount>& drive_objects() { return kObjects; }

std::optional<DriveObject> drive_object_from_key(const std::string& key) {
  for (const auto& info : kObjects) {
    if (key == info.key) return info.object;
  }
  return std::nullopt;
}

const RegisterPlacement& ModbusMap::at(DriveObject object) const {
  const auto& placement = find(object);
  if (!placement) throw std::logic_error(std::string("modbus map: no register for ") + object_info(object).key);
  return *placement;
}

std::optional<std::pair<DriveObject, std::uint16_t>> ModbusMap::object_at(std::uint16_t address) const {
  for (const auto& info : kObjects) {
    const auto& placement = find(info.object);
    if (placement && address >= placement->address && address - placement->address < placement->count()) {
      return std::make_pair(info.object, static_cast<std::uint16_t>(address - placement->address));
    }
  }
  return std::nullopt;
}

void ModbusMap::validate() const {
  const auto fail = [&](const std::string& path, const std::string& problem) {
    throw std::invalid_argument(origin + ": " + path + ": " + problem);
  };
  for (const auto& info : kObjects) {
    const std::string path = std::string("registers.") + info.key;
    const auto& placement = find(info.object);
    if (!placement) {
      if (info.required) fail("registers", fmt::format("missing {} (0x{:04X}, required)", info.key, info.index));
      continue;
    }
    if (is_word(info.object) && placement->type != RegisterType::uint16) {
      fail(path + ".type", std::string("expected \"uint16\" (a CiA 402 word), got \"") +
                               register_type_name(placement->type) + "\"");
    }
    if (is_mode(info.object) && placement->type != RegisterType::int16 && placement->type != RegisterType::uint16) {
      fail(path + ".type", std::string("expected \"int16\" or \"uint16\" (a mode of operation), got \"") +
                               register_type_name(placement->type) + "\"");
    }
    if (placement->address + placement->count() - 1 > 65535) {
      fail(path + ".address", fmt::format("expected 0..65534 for a 32-bit object (it takes two registers), got {}",
                                          placement->address));
    }
    if (info.scale_unit == nullptr) {
      if (placement->scale != 1.0) fail(path + ".scale", "takes no scale (a CiA 402 word or mode)");
    } else if (info.object == DriveObject::quick_stop_deceleration) {
      if (!(placement->scale > 0.0) || !std::isfinite(placement->scale)) {
        fail(path + ".scale", fmt::format("expected a finite positive number ({})", info.scale_unit));
      }
    } else if (!std::isfinite(placement->scale) || placement->scale == 0.0) {
      fail(path + ".scale", fmt::format("expected a finite non-zero number ({})", info.scale_unit));
    }
    for (const auto& other : kObjects) {
      if (other.object >= info.object) break;
      const auto& them = find(other.object);
      if (!them) continue;
      const bool apart = placement->address + placement->count() <= them->address ||
                         them->address + them->count() <= placement->address;
      if (!apart) {
        fail(path, fmt::format("{} overlap registers.{} ({})", registers_text(*placement), other.key,
                               registers_text(*them)));
      }
    }
  }
  const auto positive = [&](double value, const char* key, const char* unit) {
    if (!(value > 0.0)) fail(std::string("limits.") + key, std::string("expected a positive number (") + unit + ")");
  };
  positive(limits.command, "command", "the plant's input unit");
  positive(limits.velocity_m_s, "velocity_m_s", "m/s");
  positive(limits.slew_per_s, "slew_per_s", "the plant's input unit per second");
  if (!(limits.position_min_m < limits.position_max_m)) {
    fail("limits.position_window_m", "expected [MIN, MAX] in metres with MIN < MAX");
  }
}

std::uint16_t ModbusMap::to_words(DriveObject object, double value, std::array<std::uint16_t, 2>& words) const {
  const RegisterPlacement& placement = at(object);
  const DriveObjectInfo& info = object_info(object);
  const Range range = type_range(placement.type);
  const double units = std::nearbyint(value * placement.scale);
  if (!(units >= range.min && units <= range.max)) {
    // The range in SI units, with the ends in order whatever the scale's sign.
    const double a = range.min / placement.scale, b = range.max / placement.scale;
    const std::string unit = info.unit[0] ? std::string(" ") + info.unit : std::string();
    if (info.scale_unit == nullptr) {
      throw std::out_of_range(fmt::format("{}: {:g} does not fit {} ({:g} to {:g})", info.key, value,
                                          register_type_name(placement.type), range.min, range.max));
    }
    throw std::out_of_range(fmt::format("{}: {:g}{} does not fit {} at {:g} {} (range {:g} to {:g}{})", info.key,
                                        value, unit, register_type_name(placement.type), placement.scale, info.scale_unit,
                                        std::min(a, b), std::max(a, b), unit));
  }
  // Two's complement of the integer, as the drive keeps it.
  const auto bits = static_cast<std::uint32_t>(static_cast<std::int64_t>(units));
  if (placement.count() == 1) {
    words[0] = static_cast<std::uint16_t>(bits & 0xFFFFu);
    return 1;
  }
  const auto high = static_cast<std::uint16_t>(bits >> 16), low = static_cast<std::uint16_t>(bits & 0xFFFFu);
  words[0] = high_word_first ? high : low;
  words[1] = high_word_first ? low : high;
  return 2;
}

double ModbusMap::from_words(DriveObject object, const std::uint16_t* words) const {
  const RegisterPlacement& placement = at(object);
  double units = 0.0;
  switch (placement.type) {
    case RegisterType::uint16: units = words[0]; break;
    case RegisterType::int16: units = static_cast<std::int16_t>(words[0]); break;
    case RegisterType::uint32:
    case RegisterType::int32: {
      const std::uint32_t high = high_word_first ? words[0] : words[1];
      const std::uint32_t low = high_word_first ? words[1] : words[0];
      const std::uint32_t bits = (high << 16) | low;
      units = placement.type == RegisterType::uint32 ? static_cast<double>(bits)
                                                     : static_cast<double>(static_cast<std::int32_t>(bits));
      break;
    }
  }
  return units / placement.scale;
}

ModbusMap default_modbus_map() {
  ModbusMap map;
  const auto place = [&](DriveObject object, std::uint16_t address, RegisterType type, double scale = 1.0) {
    map.registers[static_cast<std::size_t>(object)] = RegisterPlacement{address, type, scale};
  };
  constexpr double kCountsPerMetre = 1e9;        // a 1 nm linear encoder: +-2.1 m in an int32
  constexpr double kVelocityUnitsPerMS = 1e6;     // 1 um/s
  constexpr double kTorqueUnitsPerInput = 1e6;    // 1e-6 of the plant's input unit: +-2147 units
  constexpr double kDecelerationUnitsPerMS2 = 1e6;  // 1 um/s^2
  // Read each cycle: one block, one request.
  place(DriveObject::statusword, 0, RegisterType::uint16);
  place(DriveObject::modes_of_operation_display, 1, RegisterType::int16);
  place(DriveObject::error_code, 2, RegisterType::uint16);
  place(DriveObject::position_actual, 3, RegisterType::int32, kCountsPerMetre);
  place(DriveObject::velocity_actual, 5, RegisterType::int32, kVelocityUnitsPerMS);
  place(DriveObject::torque_actual, 7, RegisterType::int32, kTorqueUnitsPerInput);
  // Written by the master.
  place(DriveObject::controlword, 16, RegisterType::uint16);
  place(DriveObject::modes_of_operation, 17, RegisterType::int16);
  place(DriveObject::target_position, 18, RegisterType::int32, kCountsPerMetre);
  place(DriveObject::target_velocity, 20, RegisterType::int32, kVelocityUnitsPerMS);
  place(DriveObject::target_torque, 22, RegisterType::int32, kTorqueUnitsPerInput);
  place(DriveObject::quick_stop_deceleration, 24, RegisterType::uint32, kDecelerationUnitsPerMS2);
  return map;
}

}  // namespace netmc::drive::modbus
