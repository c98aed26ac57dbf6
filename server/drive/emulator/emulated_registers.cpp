#include "server/drive/emulator/emulated_registers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace netmc::drive::emulator {
namespace {

using modbus::DriveObject;

std::size_t slot(DriveObject object) { return static_cast<std::size_t>(object); }

std::string registers_text(const modbus::RegisterPlacement& placement) {
  if (placement.count() == 1) return fmt::format("register {}", placement.address);
  return fmt::format("registers {}-{}", placement.address, placement.address + placement.count() - 1);
}

}  // namespace

EmulatedRegisters::EmulatedRegisters(const modbus::ModbusMap& map, EmulatedDrive& drive) : map_(map), drive_(drive) {
  // What the master's objects hold before it writes them: the drive's own settings, a position
  // target where the axis stands.
  const auto initial = [&](DriveObject object, double value) {
    if (!map_.has(object)) return;
    try {
      map_.to_words(object, value, written_[slot(object)]);
    } catch (const std::out_of_range&) {
      // Left zero: the drive's value does not fit the map's type.
    }
  };
  initial(DriveObject::controlword, 0.0);
  initial(DriveObject::modes_of_operation, static_cast<double>(static_cast<int>(drive_.mode())));
  initial(DriveObject::target_position, drive_.position());
  initial(DriveObject::quick_stop_deceleration, drive_.settings().quick_stop_deceleration_m_s2);
}

double EmulatedRegisters::drive_value(DriveObject object) const {
  switch (object) {
    case DriveObject::statusword: return drive_.statusword();
    case DriveObject::modes_of_operation_display: return static_cast<int>(drive_.mode());
    case DriveObject::error_code: return drive_.error_code();
    case DriveObject::position_actual: return drive_.position();
    case DriveObject::velocity_actual: return drive_.velocity();
    case DriveObject::torque_actual: return drive_.input();
    default: return 0.0;
  }
}

RegisterAccess EmulatedRegisters::read(std::uint16_t address, std::uint16_t count, std::uint16_t* words) {
  const std::uint32_t end = std::uint32_t{address} + count;
  std::uint32_t next = address;
  while (next < end) {
    const auto found = map_.object_at(static_cast<std::uint16_t>(next));
    if (!found) return {kIllegalDataAddress, fmt::format("register {} is not in the map", next)};
    const auto [object, first] = *found;
    const modbus::DriveObjectInfo& info = modbus::object_info(object);
    std::array<std::uint16_t, 2> value{};
    if (info.written_by_master) {
      value = written_[slot(object)];
    } else {
      try {
        map_.to_words(object, drive_value(object), value);
      } catch (const std::out_of_range& error) {
        return {kServerDeviceFailure, error.what()};
      }
    }
    for (std::uint16_t word = first; word < map_.at(object).count() && next < end; ++word, ++next) {
      words[next - address] = value[word];
    }
  }
  return {};
}

RegisterAccess EmulatedRegisters::write(std::uint16_t address, const std::uint16_t* words, std::uint16_t count) {
  // Everything checked before anything is applied.
  struct Pending {
    DriveObject object;
    double value;
    std::array<std::uint16_t, 2> words;
  };
  std::array<Pending, modbus::kDriveObjectCount> pending{};
  std::size_t pending_count = 0;
  const std::uint32_t end = std::uint32_t{address} + count;
  std::uint32_t next = address;
  while (next < end) {
    const auto found = map_.object_at(static_cast<std::uint16_t>(next));
    if (!found) return {kIllegalDataAddress, fmt::format("register {} is not in the map", next)};
    const auto [object, first] = *found;
    const modbus::DriveObjectInfo& info = modbus::object_info(object);
    const modbus::RegisterPlacement& placement = map_.at(object);
    if (!info.written_by_master) {
      return {kIllegalDataAddress, fmt::format("{} ({}) is read-only", info.key, registers_text(placement))};
    }
    if (first != 0 || next + placement.count() > end) {
      return {kIllegalDataAddress, fmt::format("a write of {} ({}) must cover all of it", info.key,
                                               registers_text(placement))};
    }
    Pending& entry = pending[pending_count++];
    entry.object = object;
    std::copy(words + (next - address), words + (next - address) + placement.count(), entry.words.begin());
    entry.value = map_.from_words(object, entry.words.data());
    if (object == DriveObject::modes_of_operation && !operation_mode_from_code(std::llround(entry.value))) {
      return {kIllegalDataValue,
              fmt::format("modes_of_operation: {:g} is no mode this drive runs (8 csp, 9 csv, 10 cst)", entry.value)};
    }
    if (object == DriveObject::quick_stop_deceleration && !(entry.value > 0.0)) {
      return {kIllegalDataValue, "quick_stop_deceleration: must be positive"};
    }
    next += placement.count();
  }
  for (std::size_t i = 0; i < pending_count; ++i) {
    written_[slot(pending[i].object)] = pending[i].words;
    apply(pending[i].object, pending[i].value);
  }
  return {};
}

void EmulatedRegisters::apply(DriveObject object, double value) {
  switch (object) {
    case DriveObject::controlword: drive_.apply_controlword(static_cast<std::uint16_t>(value)); break;
    case DriveObject::modes_of_operation: drive_.set_mode(*operation_mode_from_code(std::llround(value))); break;
    case DriveObject::target_position: drive_.set_target(OperationMode::csp, value); break;
    case DriveObject::target_velocity: drive_.set_target(OperationMode::csv, value); break;
    case DriveObject::target_torque: drive_.set_target(OperationMode::cst, value); break;
    case DriveObject::quick_stop_deceleration: drive_.set_quick_stop_deceleration(value); break;
    default: break;
  }
}

}  // namespace netmc::drive::emulator
