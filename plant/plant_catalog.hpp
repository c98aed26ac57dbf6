#pragma once
// Named plant sets for the CLI (--plant NAME) and the job specs: one AxisPlant per axis with the
// parameters of the source paper. The reasoning behind every number is in plant_catalog.cpp.

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "plant/axis_plant.hpp"
#include "plant/second_order_axis.hpp"

namespace netmc::plant {

struct AxisSet {
  std::vector<std::unique_ptr<AxisPlant>> axes;
  std::string description;
};

// "seed001", "ballscrew", "linmotor", "stage004".
std::vector<std::string> plant_names();

// axis_count 1..3 (X, Y, and a third axis with the Y parameters). Throws std::invalid_argument
// for an unknown name ("plant: unknown name 'x' (expected one of: ...)") or a bad axis_count.
AxisSet make_plant_set(std::string_view name, std::size_t axis_count);

// Paper 001 axis parameters used by "seed001" (axis 0 = X, 1 = Y, 2 = copy of Y). The single
// place to recalibrate the friction level (digest 1.7 [A]).
SecondOrderAxisParameters seed001_axis_parameters(std::size_t axis);

}  // namespace netmc::plant
