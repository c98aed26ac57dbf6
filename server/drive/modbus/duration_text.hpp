#pragma once
// Durations as the Modbus drive spec and netmc-drive-emulator's flags write them: a decimal
// number with its unit, s, ms or us ("20ms", "0.5s", "250us"); "0" alone for none.

#include <string>

namespace netmc::drive::modbus {

// Seconds. Throws std::invalid_argument("FIELD: expected a duration such as 20ms, 0.5s or 250us,
// got '…'") for anything else, and for a negative or non-finite one.
double parse_duration_s(const std::string& text, const std::string& field);
// "50 ms", "250 us", "1.5 s": three significant digits in the unit that suits.
std::string format_duration(double seconds);

}  // namespace netmc::drive::modbus
