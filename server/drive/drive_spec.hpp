#pragma once
// What `netmc-axis --drive` names: netmc's simulated drive of a plant (sim:PLANT[:KEY=VALUE,...]),
// a Modbus TCP drive (modbus-tcp:HOST:PORT[,unit=N,map=FILE,timeout=..]) or a lab's plugin
// (plugin:PATH.so[:KEY=VALUE,...]). The flag takes one spec for every axis of the node, or
// AXIS=SPEC entries (repeated) for one axis each.

#include <map>
#include <string>
#include <vector>

namespace netmc::drive {

struct DriveSpec {
  enum class Kind { simulated, modbus_tcp, plugin };
  Kind kind = Kind::simulated;
  std::string text;  // what follows "KIND:"

  std::string describe() const;  // "sim:seed001", "modbus-tcp:127.0.0.1:1502,unit=1"
  // sim: the plant's name and its overrides (KEY=VALUE after the plant's name).
  std::string plant() const;
  std::vector<std::pair<std::string, double>> plant_overrides() const;
};

// True when the whole of `text` is a finite decimal number (then in `value`): flag values are
// decimal only (no hexadecimal, "inf" or "nan" as strtod would take).
bool parse_finite_decimal(const std::string& text, double& value);

// Throws std::invalid_argument naming --drive and the expected forms.
DriveSpec parse_drive_spec(const std::string& text);

// The drive of every axis of a node from the --drive values: none (sim of `plant` for every
// axis), one spec for every axis, or AXIS=SPEC entries (an axis without one gets the spec given
// for every axis, else sim of `plant`). A Modbus or plugin drive serves one axis: the same such
// spec for two axes is refused. Throws std::invalid_argument naming --drive.
std::map<std::string, DriveSpec> parse_drive_flags(const std::vector<std::string>& values,
                                                   const std::vector<std::string>& axes, const std::string& plant);

}  // namespace netmc::drive
