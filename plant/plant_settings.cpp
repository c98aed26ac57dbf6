#include "plant/plant_settings.hpp"

#include <sstream>

namespace netmc::plant {

void require_non_negative_value(const std::string& key, double value) {
  if (!(value >= 0.0)) {
    throw std::invalid_argument("plant: " + key + " must be >= 0 (got " + std::to_string(value) + ")");
  }
}

// Thesis eq. 5-2: hiwin's dead zone is part of its model; every other plant takes one per axis
// through the same keys (thesis section 5.5: a contouring stage whose drives have dead zones),
// none by default.
std::vector<PlantSetting<DeadZoneParameters>> dead_zone_settings(const DeadZoneParameters& nominal,
                                                                 const std::string& unit) {
  using P = DeadZoneParameters;
  const auto number = [](double v) {
    std::ostringstream text;  // shortest form: 1.2, -1, 0.9
    text << v;
    return text.str();
  };
  return {
      {"dead_zone_right_v", "b_r, right break point of the input dead zone (" + unit + "), >= 0; " + number(nominal.right_break_v),
       [](P& p, double v) { p.right_break_v = v; }},
      {"dead_zone_left_v", "b_l, left break point of the input dead zone (" + unit + "), <= 0; " + number(nominal.left_break_v),
       [](P& p, double v) { p.left_break_v = v; }},
      {"dead_zone_right_slope", "m_r, right slope of the dead zone (" + unit + "/" + unit + "), > 0; " + number(nominal.right_slope),
       [](P& p, double v) { p.right_slope = v; }},
      {"dead_zone_left_slope", "m_l, left slope of the dead zone (" + unit + "/" + unit + "), > 0; " + number(nominal.left_slope),
       [](P& p, double v) { p.left_slope = v; }},
  };
}

}  // namespace netmc::plant
