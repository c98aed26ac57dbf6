#pragma once
// Locale-independent number and duration text for describe() strings and error messages.
// Durations are stored in seconds but read best in ms or us, so the unit is chosen by size.
// std::to_chars is used instead of printf/streams so a user locale cannot change the output.

#include <string>

namespace netmc::netsim {

// Shortest readable form with 6 significant digits: "0.002", "1e-07", "nan", "inf".
std::string format_number(double value);

// Seconds shown in s, ms or us depending on magnitude: "1.5 s", "0.3 ms", "50 us", "inf s".
std::string format_duration(double seconds);

}  // namespace netmc::netsim
