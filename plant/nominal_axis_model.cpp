#include "plant/nominal_axis_model.hpp"

#include "plant/plant_registry.hpp"

namespace netmc::plant {

std::optional<NominalAxisModel> nominal_axis_model(std::string_view plant_name, std::size_t axis) {
  if (axis > 2) return std::nullopt;
  const PlantModel* model = PlantRegistry::global().find(plant_name);
  if (!model || !model->nominal_model) return std::nullopt;
  return model->nominal_model(axis);
}

}  // namespace netmc::plant
