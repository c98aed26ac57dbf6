#pragma once
// Where a Modbus TCP drive keeps its CiA 402 objects: one holding register (16-bit) or two
// (32-bit) per object, the type and word order of each, and the scale from netmc's SI values to
// the drive's own units. Vendors differ in all of these, so a map file (modbus_map_file.hpp) says
// it per drive; default_modbus_map() is netmc's own layout, the one netmc-drive-emulator serves
// unless told otherwise (its file form: default-map.json next to this header).
//
// Values cross the map in SI units (m, m/s, m/s^2 and the plant's input unit for torque); the
// CiA 402 words (controlword, statusword, error code) and the modes cross it as their integers.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "server/drive/axis_limits.hpp"
#include "server/drive/drive.hpp"

namespace netmc::drive::modbus {

enum class RegisterType : std::uint8_t { uint16, int16, uint32, int32 };
const char* register_type_name(RegisterType type);  // "uint16", ...
std::optional<RegisterType> register_type_from_name(const std::string& name);
// Registers an object of `type` takes: 1 or 2.
std::uint16_t register_count(RegisterType type);

// The CiA 402 objects a map places.
enum class DriveObject : std::uint8_t {
  controlword,                 // 0x6040
  statusword,                  // 0x6041
  modes_of_operation,          // 0x6060
  modes_of_operation_display,  // 0x6061
  target_position,             // 0x607A
  target_velocity,             // 0x60FF
  target_torque,               // 0x6071
  position_actual,             // 0x6064
  velocity_actual,             // 0x606C
  torque_actual,               // 0x6077
  error_code,                  // 0x603F
  quick_stop_deceleration,     // 0x6085
};
inline constexpr std::size_t kDriveObjectCount = 12;

// What the map and its file need to know of an object.
struct DriveObjectInfo {
  DriveObject object;
  const char* key;         // its name in a map file: "target_position"
  std::uint16_t index;     // its CiA 402 object index: 0x607A
  bool required;           // a map must place it
  bool written_by_master;  // the master writes it (else the drive does, and it is read-only)
  // What a scale counts ("counts per metre", "drive units per m/s", ...); nullptr for the words
  // and modes, which take no scale.
  const char* scale_unit;
  const char* unit;        // the SI unit in messages: "m", "m/s", "" (the plant's input), "m/s^2"
};
const DriveObjectInfo& object_info(DriveObject object);
// Every object, in DriveObject order.
const std::array<DriveObjectInfo, kDriveObjectCount>& drive_objects();
// The object a map file calls `key`, if any.
std::optional<DriveObject> drive_object_from_key(const std::string& key);

struct RegisterPlacement {
  std::uint16_t address = 0;  // its first holding register
  RegisterType type = RegisterType::uint16;
  double scale = 1.0;         // drive units per SI unit (1 for the words and modes)

  std::uint16_t count() const { return register_count(type); }
  bool operator==(const RegisterPlacement&) const = default;
};

struct ModbusMap {
  std::array<std::optional<RegisterPlacement>, kDriveObjectCount> registers;
  bool high_word_first = true;  // word order of the 32-bit objects
  std::uint8_t unit_id = 1;     // the drive's unit unless the drive spec names another
  OperationMode job_mode = OperationMode::cst;
  AxisLimits limits;            // what the drive's configuration states (none unless given)
  std::string origin = "default map";  // for messages: "map file lab.json"

  const std::optional<RegisterPlacement>& find(DriveObject object) const {
    return registers[static_cast<std::size_t>(object)];
  }
  bool has(DriveObject object) const { return find(object).has_value(); }
  // The placement of a required object (or any placed one); std::logic_error if absent.
  const RegisterPlacement& at(DriveObject object) const;
  // The object one of whose registers is `address`, and which of its registers it is (0, 1).
  std::optional<std::pair<DriveObject, std::uint16_t>> object_at(std::uint16_t address) const;

  // Throws std::invalid_argument naming `origin` and the key path: a required object missing,
  // an object past register 65535, two objects sharing a register, a type an object cannot
  // have, a scale that is not a finite non-zero number, a limit that is not positive.
  void validate() const;

  // `value` (SI; the integer itself for the words and modes) as the object's register words,
  // rounded to the nearest drive unit, in the map's word order; returns how many words (1, 2).
  // Throws std::out_of_range naming the object, the value and the range it must lie in.
  std::uint16_t to_words(DriveObject object, double value, std::array<std::uint16_t, 2>& words) const;
  // The inverse: the object's value from its register words (words[0] at its first register).
  double from_words(DriveObject object, const std::uint16_t* words) const;
};

// netmc's own layout (default-map.json, in the same words): everything a master reads each
// cycle in one block from register 0, everything it writes in a second block from register 16.
//   0 statusword, 1 modes display, 2 error code, 3-4 position actual (int32, 1 nm), 5-6 velocity
//   actual (int32, 1 um/s), 7-8 torque actual (int32, 1e-6 of the plant's input);
//   16 controlword, 17 modes of operation, 18-19 target position, 20-21 target velocity,
//   22-23 target torque (same scales), 24-25 quick stop deceleration (uint32, 1 um/s^2).
// High word first, unit 1, jobs in CST, no limits.
ModbusMap default_modbus_map();

}  // namespace netmc::drive::modbus
