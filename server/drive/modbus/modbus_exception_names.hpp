#pragma once
// The names the Modbus application protocol (V1.1b3, section 7) gives its exception codes, for
// messages on both ends: "Modbus exception 4 (server device failure)".

#include <cstdint>
#include <string>

namespace netmc::drive::modbus {

// "illegal data address"; "unknown exception" for a code the protocol does not define.
const char* modbus_exception_name(std::uint8_t code);
// "Modbus exception 2 (illegal data address)".
std::string describe_modbus_exception(std::uint8_t code);

}  // namespace netmc::drive::modbus
