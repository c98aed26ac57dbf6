#pragma once
// One named plant as netmc knows it: its name, what it is and where it comes from, the unit of
// its input, the machine's travel and rated input, the parameters a job may change per axis, and
// how one of its axes is built. A plant is one file under plant/models/ and one line in
// models/registered_plants.inc; --plant, --plant-parameters, netmc sim --list-plants, spec
// checking, the axis nodes' default limits and the docs' table (docs/plants.md) take it from there.

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plant/axis_plant.hpp"
#include "plant/disturbance.hpp"
#include "plant/nominal_axis_model.hpp"

namespace netmc::plant {

// A parameter of a named plant that a job may change per axis (a payload, a friction level).
struct PlantParameter {
  std::string key;          // e.g. "load_kg"
  std::string description;  // what it is, with its unit and the default of each axis
};

// What the machine behind a named plant takes: its travel and its drive's rated input (in the
// plant's input unit). netmc-axis uses them as the default limits of a simulated drive, so that a
// node started with no limit still trips on a command or a position the machine could not take.
// Where a source gives no figure the value is an assumption, marked so in the plant's file.
struct PlantRating {
  double travel_min_m = 0.0;
  double travel_max_m = 0.0;
  double rated_input = 0.0;
};

// A job's changes to one axis of the set: parameters by key, applied in order over the axis's
// nominal ones, and a disturbance in the plant's input unit.
struct AxisOverrides {
  std::vector<std::pair<std::string, double>> parameters;
  Disturbance disturbance;
};

struct PlantModel {
  std::string name;        // "seed001"
  std::string title;       // "paper 001 eq. 3 servo axes (netmc's assumed parameters [A])"
  std::string source;      // by the short names of docs/references.md: "paper 001"
  std::string input_unit;  // where a command and an additive disturbance enter: "V", "N", "m/s^2"
  PlantRating rating;
  // The input dead zone of thesis eq. 5-2 is part of the model itself (hiwin); every other plant
  // takes one per axis through the dead_zone_* keys the catalogue adds.
  bool own_dead_zone = false;
  std::vector<PlantParameter> parameters;  // the model's own keys
  // Axis `axis` (0 = X, 1 = Y, 2 = a third axis) with `overrides` (null: nominal) applied. Throws
  // std::invalid_argument naming an unknown key or a value the model rejects.
  std::function<std::unique_ptr<AxisPlant>(std::size_t axis, const AxisOverrides* overrides)> make_axis;
  // The nominal model x'' = a x' + b u - c tanh(x'/v_s) of axis `axis`, where the plant is of that
  // form (a delay compensator predicts with it); unset where it is not.
  std::function<NominalAxisModel(std::size_t axis)> nominal_model;
};

}  // namespace netmc::plant
