#pragma once
// The holding registers of netmc-drive-emulator: the register map laid over an EmulatedDrive.
// A read gives the drive's state (statusword, mode display, error code, actual values) and the
// last words the master wrote to its own objects; a write reaches the drive (controlword, mode,
// targets, quick stop deceleration). What a real drive would refuse is refused with the Modbus
// exception it would answer: a register outside the map, a write to an object the drive owns or
// to part of a 32-bit object (2, illegal data address), a value the drive cannot take, such as an
// unknown mode of operation (3, illegal data value), an actual value the map's type cannot hold
// (4, server device failure). A refused write changes nothing, even of the objects before the
// one refused.

#include <array>
#include <cstdint>
#include <string>

#include "server/drive/emulated_drive.hpp"
#include "server/drive/modbus/modbus_map.hpp"

namespace netmc::drive::emulator {

// Modbus exception codes (Modbus Application Protocol 1.1b3, section 7).
inline constexpr std::uint8_t kIllegalFunction = 1;
inline constexpr std::uint8_t kIllegalDataAddress = 2;
inline constexpr std::uint8_t kIllegalDataValue = 3;
inline constexpr std::uint8_t kServerDeviceFailure = 4;
inline constexpr std::uint8_t kGatewayTargetFailed = 0x0B;  // a request for a unit this server is not

struct RegisterAccess {
  std::uint8_t exception = 0;  // 0 when done, else the Modbus exception code to answer
  std::string why;             // for the log, when refused

  bool ok() const { return exception == 0; }
};

class EmulatedRegisters {
 public:
  // Keeps references: `map` and `drive` outlive it.
  EmulatedRegisters(const modbus::ModbusMap& map, EmulatedDrive& drive);

  RegisterAccess read(std::uint16_t address, std::uint16_t count, std::uint16_t* words);
  RegisterAccess write(std::uint16_t address, const std::uint16_t* words, std::uint16_t count);

 private:
  double drive_value(modbus::DriveObject object) const;  // an object the drive owns
  void apply(modbus::DriveObject object, double value);

  const modbus::ModbusMap& map_;
  EmulatedDrive& drive_;
  std::array<std::array<std::uint16_t, 2>, modbus::kDriveObjectCount> written_{};  // the master's objects
};

}  // namespace netmc::drive::emulator
