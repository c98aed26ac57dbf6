#pragma once
// The text after `modbus-tcp:` in a drive spec: HOST:PORT[,unit=N][,map=FILE][,timeout=DURATION].
// HOST is an IPv4 address or a host name (resolved when the drive connects), PORT 1..65535; unit
// 0..255 (default: the map's unit_id), map a register map file (modbus_map_file.hpp; default:
// netmc's default map), timeout the longest wait for an answer, 1 ms..10 s (default 50 ms).

#include <cstdint>
#include <optional>
#include <string>

namespace netmc::drive::modbus {

inline constexpr double kDefaultTimeoutS = 0.05;

struct ModbusTcpSpec {
  std::string host;
  std::uint16_t port = 0;
  std::optional<std::uint8_t> unit;
  std::optional<std::string> map_path;
  double timeout_s = kDefaultTimeoutS;
};

// Throws std::invalid_argument naming the field: "modbus-tcp:drive:0: port: expected 1..65535,
// got '0'".
ModbusTcpSpec parse_modbus_tcp_spec(const std::string& text);

}  // namespace netmc::drive::modbus
