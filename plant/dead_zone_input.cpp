#include "plant/dead_zone_input.hpp"

#include <sstream>
#include <stdexcept>
#include <utility>

#include "plant/parameter_checks.hpp"

namespace netmc::plant {
namespace {

constexpr const char* kDeadZoneInputOwner = "DeadZoneInput";

}  // namespace

void validate_dead_zone(const DeadZoneParameters& p) {
  require_non_negative(kDeadZoneInputOwner, "right_break_v", p.right_break_v);
  require_finite(kDeadZoneInputOwner, "left_break_v", p.left_break_v);
  if (p.left_break_v > 0.0) {
    std::ostringstream text;
    text << kDeadZoneInputOwner << ": left_break_v must be <= 0 (got " << p.left_break_v << ")";
    throw std::invalid_argument(text.str());
  }
  require_positive(kDeadZoneInputOwner, "right_slope", p.right_slope);
  require_positive(kDeadZoneInputOwner, "left_slope", p.left_slope);
}

DeadZoneInput::DeadZoneInput(DeadZoneParameters dead_zone, std::unique_ptr<AxisPlant> inner)
    : dead_zone_(dead_zone), inner_(std::move(inner)) {
  validate_dead_zone(dead_zone_);
  if (!inner_) throw std::invalid_argument("DeadZoneInput: inner plant must not be null");
}

void DeadZoneInput::advance(double duration_s, double input) {
  require_advance_arguments(kDeadZoneInputOwner, duration_s, input);
  inner_->advance(duration_s, dead_zone_output(dead_zone_, input));
}

std::unique_ptr<AxisPlant> DeadZoneInput::clone() const {
  return std::make_unique<DeadZoneInput>(dead_zone_, inner_->clone());
}

std::string DeadZoneInput::describe() const {
  std::ostringstream text;
  text << "dead zone w = " << dead_zone_.right_slope << "(v - " << dead_zone_.right_break_v << ") | 0 | "
       << dead_zone_.left_slope << "(v - " << dead_zone_.left_break_v << ") -> " << inner_->describe();
  return text.str();
}

}  // namespace netmc::plant
