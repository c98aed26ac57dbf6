#pragma once
// Named plant sets for the CLI (--plant NAME) and the job specs: one AxisPlant per axis with the
// parameters of the source paper. Each plant is a PlantModel of plant/models/ (its file gives the
// reasoning behind every number); these functions look it up in the PlantRegistry.

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "plant/axis_plant.hpp"
#include "plant/plant_model.hpp"
#include "plant/second_order_axis.hpp"

namespace netmc::plant {

struct AxisSet {
  std::vector<std::unique_ptr<AxisPlant>> axes;
  std::string description;
};

// "seed001", "ballscrew", "linmotor", "stage004", "linmotor-flex", "hiwin" (the registry's order).
std::vector<std::string> plant_names();

// A plant read from a file, fmu:PATH.fmu[:...] or plugin:PATH.so[:...]: not the catalog's (the
// job layer makes it, server/job/plant_source.hpp); the whole text is its name.
bool is_file_plant(std::string_view name);

// The keys `name` takes (its own, then the input dead zone's where the model has none of its
// own); throws std::invalid_argument for an unknown plant.
std::vector<PlantParameter> plant_parameters(std::string_view name);
// The unit of the plant's input, where an additive disturbance enters (V, N, m/s^2).
std::string plant_input_unit(std::string_view name);
// Throws std::invalid_argument for an unknown plant.
PlantRating plant_rating(std::string_view name);

// axis_count 1..3 (X, Y, and a third axis with the Y parameters); `overrides` has at most
// axis_count entries (axis 0 first; missing ones change nothing). Throws std::invalid_argument
// for an unknown name ("plant: unknown name 'x' (expected one of: ...)"), a bad axis_count, an
// unknown key (naming the plant and its keys) or a value the model rejects.
AxisSet make_plant_set(std::string_view name, std::size_t axis_count,
                       const std::vector<AxisOverrides>& overrides = {});

// Paper 001 axis parameters used by "seed001" (axis 0 = X, 1 = Y, 2 = copy of Y). The single
// place to recalibrate the friction level (netmc's assumption [A]: the paper gives no plant numbers).
SecondOrderAxisParameters seed001_axis_parameters(std::size_t axis);

}  // namespace netmc::plant
