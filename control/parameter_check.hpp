#pragma once
// Parameter validation shared by the controllers: one message that names the field and the
// expected form, thrown as std::invalid_argument.

#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

namespace netmc::control {

inline double require_finite(double value, std::string_view field) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(std::string(field) + ": expected a finite number, got " +
                                std::to_string(value));
  }
  return value;
}

inline double require_positive(double value, std::string_view field) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw std::invalid_argument(std::string(field) + ": expected a positive finite number, got " +
                                std::to_string(value));
  }
  return value;
}

inline double require_non_negative(double value, std::string_view field) {
  if (!std::isfinite(value) || value < 0.0) {
    throw std::invalid_argument(std::string(field) +
                                ": expected a non-negative finite number, got " +
                                std::to_string(value));
  }
  return value;
}

inline double require_in_unit_interval(double value, std::string_view field) {
  if (!std::isfinite(value) || value < 0.0 || value > 1.0) {
    throw std::invalid_argument(std::string(field) + ": expected a number in [0, 1], got " +
                                std::to_string(value));
  }
  return value;
}

}  // namespace netmc::control
