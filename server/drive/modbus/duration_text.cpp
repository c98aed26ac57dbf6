#include "server/drive/modbus/duration_text.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "server/drive/drive_spec.hpp"

namespace netmc::drive::modbus {

double parse_duration_s(const std::string& text, const std::string& field) {
  const auto bad = [&] {
    return std::invalid_argument(field + ": expected a duration such as 20ms, 0.5s or 250us, got '" +
                                 text.substr(0, 40) + (text.size() > 40 ? "...'" : "'"));
  };
  if (text == "0") return 0.0;
  double scale = 1.0;
  std::string number;
  if (text.size() > 2 && text.compare(text.size() - 2, 2, "ms") == 0) {
    scale = 1e-3;
    number = text.substr(0, text.size() - 2);
  } else if (text.size() > 2 && text.compare(text.size() - 2, 2, "us") == 0) {
    scale = 1e-6;
    number = text.substr(0, text.size() - 2);
  } else if (text.size() > 1 && text.back() == 's') {
    number = text.substr(0, text.size() - 1);
  } else {
    throw bad();
  }
  double value = 0.0;
  if (!parse_finite_decimal(number, value) || value < 0.0) throw bad();
  return value * scale;
}

std::string format_duration(double seconds) {
  const double magnitude = std::abs(seconds);
  if (magnitude >= 1.0) return fmt::format("{:.3g} s", seconds);
  if (magnitude >= 1e-3) return fmt::format("{:.3g} ms", seconds * 1e3);
  return fmt::format("{:.3g} us", seconds * 1e6);
}

}  // namespace netmc::drive::modbus
