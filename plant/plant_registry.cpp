#include "plant/plant_registry.hpp"

#include <sstream>
#include <stdexcept>

namespace netmc::plant {

const PlantRegistry& PlantRegistry::global() {
  static const PlantRegistry registry = [] {
    PlantRegistry built_in;
    // One line per plant file (plant/models/).
#define NETMC_PLANT(name) register_##name(built_in);
#include "plant/models/registered_plants.inc"
#undef NETMC_PLANT
    return built_in;
  }();
  return registry;
}

void PlantRegistry::add(PlantModel model) {
  if (find(model.name)) throw std::logic_error("plant " + model.name + " registered twice");
  models_.push_back(std::move(model));
}

const PlantModel* PlantRegistry::find(std::string_view name) const {
  for (const auto& model : models_) {
    if (model.name == name) return &model;
  }
  return nullptr;
}

const PlantModel& PlantRegistry::at(std::string_view name) const {
  if (const auto* model = find(name)) return *model;
  throw std::invalid_argument("plant: unknown name '" + std::string(name) + "' (expected one of: " + names_text() + ")");
}

std::string PlantRegistry::names_text() const {
  std::string out;
  for (const auto& model : models_) {
    if (!out.empty()) out.append(", ");
    out.append(model.name);
  }
  return out;
}

std::string PlantRegistry::markdown_table() const {
  std::string out =
      "| plant | model | source | input | travel [m] | rated input | parameters (`--plant NAME:KEY=VALUE`) |\n"
      "| --- | --- | --- | --- | --- | --- | --- |\n";
  for (const auto& model : models_) {
    std::string keys;
    for (const auto& parameter : model.parameters) {
      if (!keys.empty()) keys.append(", ");
      keys.append("`").append(parameter.key).append("`");
    }
    std::ostringstream row;  // numbers in their shortest form, as %g
    row << "| `" << model.name << "` | " << model.title << " | " << model.source << " | " << model.input_unit << " | "
        << model.rating.travel_min_m << " .. " << model.rating.travel_max_m << " | " << model.rating.rated_input << " "
        << model.input_unit << " | " << keys << " |\n";
    out += row.str();
  }
  return out;
}

}  // namespace netmc::plant
