#pragma once
// The parameters of a plant model that a job may change, as settings of its parameter struct P:
// a key, its description (unit and nominal values) and how a value changes P. A plant's file
// lists its settings once; the descriptor's parameter list and the overrides both come from it.

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "plant/dead_zone_input.hpp"
#include "plant/plant_model.hpp"

namespace netmc::plant {

template <class P>
struct PlantSetting {
  std::string key;
  std::string description;
  std::function<void(P&, double)> apply;
};

// Throws std::invalid_argument "plant: KEY must be >= 0 (got V)" for a negative or NaN value.
void require_non_negative_value(const std::string& key, double value);

// The input dead zone of thesis eq. 5-2 in front of an axis, its four keys; `nominal` gives the
// defaults the descriptions show, `unit` the input unit.
std::vector<PlantSetting<DeadZoneParameters>> dead_zone_settings(const DeadZoneParameters& nominal,
                                                                 const std::string& unit);

template <class P>
std::vector<PlantParameter> describe_settings(const std::vector<PlantSetting<P>>& settings) {
  std::vector<PlantParameter> out;
  for (const auto& s : settings) out.push_back({s.key, s.description});
  return out;
}

// The axis's nominal parameters with the job's overrides applied in order, and its disturbance.
template <class P>
P with_overrides(P p, const std::vector<PlantSetting<P>>& settings, const AxisOverrides* overrides,
                 std::string_view plant_name) {
  if (!overrides) return p;
  for (const auto& [key, value] : overrides->parameters) {
    if (!std::isfinite(value)) {
      throw std::invalid_argument("plant: " + key + " must be a finite number (got " + std::to_string(value) + ")");
    }
    const auto it = std::find_if(settings.begin(), settings.end(), [&](const auto& s) { return s.key == key; });
    if (it == settings.end()) {
      std::string keys;
      for (const auto& s : settings) keys += (keys.empty() ? "" : ", ") + s.key;
      throw std::invalid_argument("plant: " + std::string(plant_name) + " has no parameter '" + key.substr(0, 64) +
                                  "' (expected one of: " + keys + ")");
    }
    it->apply(p, value);
  }
  p.disturbance = overrides->disturbance;
  return p;
}

}  // namespace netmc::plant
