#include "server/job/dead_zone_spec.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace netmc::job {

control::DeadZoneEstimate build_dead_zone(const netmc::v1::DeadZoneSpec& d, const std::string& field) {
  const auto within = [&](double value, double low, double high, const char* name, const char* form) {
    if (!(value >= low && value <= high)) {
      throw std::invalid_argument(field + "." + name + ": expected " + form + ", got " + fmt::format("{:g}", value));
    }
  };
  within(d.right_break_v(), 0.0, 1e3, "right_break_v", "a voltage in [0, 1000]");
  within(d.left_break_v(), -1e3, 0.0, "left_break_v", "a voltage in [-1000, 0]");
  within(d.right_slope(), 1e-6, 1e6, "right_slope", "a slope in [1e-6, 1e6]");
  within(d.left_slope(), 1e-6, 1e6, "left_slope", "a slope in [1e-6, 1e6]");
  return {d.right_slope(), d.right_slope() * d.right_break_v(), d.left_slope(), d.left_slope() * d.left_break_v()};
}

}  // namespace netmc::job
