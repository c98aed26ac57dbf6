#pragma once
// Every named plant netmc builds in (plant/models/, one file and one line each), in the order of
// --help, the error messages and the docs' table.

#include <string>
#include <string_view>
#include <vector>

#include "plant/plant_model.hpp"

namespace netmc::plant {

class PlantRegistry {
 public:
  // The built-in plants (and the test suite's own in its build).
  static const PlantRegistry& global();

  // Throws std::logic_error for a name registered twice.
  void add(PlantModel model);
  const std::vector<PlantModel>& models() const { return models_; }
  const PlantModel* find(std::string_view name) const;
  // As find; throws std::invalid_argument "plant: unknown name 'x' (expected one of: ...)".
  const PlantModel& at(std::string_view name) const;
  // "seed001, ballscrew, ..."
  std::string names_text() const;
  // The docs' table (docs/plants.md; netmc sim --list-plants): name, model, source, input unit,
  // travel, rated input, the keys --plant NAME:KEY=VALUE takes.
  std::string markdown_table() const;

 private:
  std::vector<PlantModel> models_;
};

#define NETMC_PLANT(name) void register_##name(PlantRegistry& registry);
#include "plant/models/registered_plants.inc"
#undef NETMC_PLANT

}  // namespace netmc::plant
