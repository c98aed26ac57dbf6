#include "control/dead_zone/dead_zone_inverse.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "control/parameter_check.hpp"

namespace netmc::control {

void DeadZoneEstimate::validate(std::string_view field) const {
  const std::string prefix(field);
  require_positive(right_slope, prefix + ".right_slope");
  require_non_negative(right_product, prefix + ".right_product");
  require_positive(left_slope, prefix + ".left_slope");
  if (!std::isfinite(left_product) || left_product > 0.0) {
    std::ostringstream text;
    text << prefix << ".left_product: expected a non-positive finite number, got " << left_product;
    throw std::invalid_argument(text.str());
  }
}

double DeadZoneInverse::invert(double demand, const DeadZoneEstimate& p) {
  bool right = demand > 0.0;  // thesis (5-5)
  if (demand == 0.0) {
    // (5-5)/(5-6): the branch of the nearer break point; ties go right.
    right = std::abs(last_command_ - p.left_break()) >= std::abs(last_command_ - p.right_break());
  }
  last_command_ = right ? (demand + p.right_product) / p.right_slope : (demand + p.left_product) / p.left_slope;
  return last_command_;
}

}  // namespace netmc::control
