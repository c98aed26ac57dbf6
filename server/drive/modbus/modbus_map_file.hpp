#pragma once
// A Modbus register map as a JSON file (default-map.json is netmc's own, and the example):
//
//   {
//     "format": "netmc-modbus-map", "version": 1,
//     "description": "free text (optional)",
//     "unit_id": 1,                  // 0..255, the drive's unit unless the drive spec names one
//     "high_word_first": true,       // word order of the 32-bit objects
//     "job_mode": "cst",             // "cst", "csv" or "csp": the mode a job's commands are in
//     "registers": {
//       "position_actual": { "address": 3, "type": "int32", "scale": 1e9 },
//       ...                           // one entry per CiA 402 object (modbus_map.hpp)
//     },
//     "limits": {                    // optional, each key optional: what the drive states
//       "command": 10, "position_window_m": [-0.1, 0.2], "velocity_m_s": 0.5, "slew_per_s": 1000
//     }
//   }
//
// Types are uint16, int16, uint32, int32; the words take uint16, the modes int16 or uint16. A
// scale (drive units per SI unit: counts per metre, per m/s, per unit of the plant's input, per
// m/s^2) is required for the SI-valued objects and refused for the others. Comments (// and /* */)
// are allowed. Everything is checked: at most 64 KiB, no unknown or repeated key, every required
// object, addresses in range and apart; each problem is one std::invalid_argument naming the file,
// the key path and the expected form.

#include <cstddef>
#include <string>
#include <string_view>

#include "server/drive/modbus/modbus_map.hpp"

namespace netmc::drive::modbus {

inline constexpr std::size_t kMaxMapFileBytes = 64 * 1024;
inline constexpr const char* kMapFormat = "netmc-modbus-map";
inline constexpr int kMapVersion = 1;

// `origin` names the text in messages ("map file lab.json").
ModbusMap parse_modbus_map(std::string_view text, const std::string& origin);
// Reads and parses the file at `path` (its origin: "map file PATH").
ModbusMap load_modbus_map(const std::string& path);

}  // namespace netmc::drive::modbus
