#include "netsim/text_format.hpp"

#include <array>
#include <charconv>
#include <cmath>

namespace netmc::netsim {

std::string format_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  std::array<char, 32> buffer{};
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::general, 6);
  return std::string(buffer.data(), result.ptr);
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds)) return format_number(seconds) + " s";
  const double magnitude = std::abs(seconds);
  if (magnitude == 0.0) return "0 ms";
  if (magnitude >= 1.0) return format_number(seconds) + " s";
  // Network delays of 0.1 ms and up read naturally in ms; shorter ones in us.
  if (magnitude >= 1e-4) return format_number(seconds * 1e3) + " ms";
  return format_number(seconds * 1e6) + " us";
}

}  // namespace netmc::netsim
