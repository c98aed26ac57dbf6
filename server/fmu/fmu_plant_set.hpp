#pragma once
// `--plant fmu:PATH.fmu[:KEY=VALUE,...]`: a plant set whose axes are instances of one FMU (FMI 2.0
// co-simulation, linux64 binary). The options are in fmu_plant_options.hpp, the plant's
// behaviour (reset, clone, failures, and what a crash inside the FMU means) in fmu_axis_plant.hpp.
//
// The FMU is loaded once per set (unpacked into a private directory, its binary dlopen-ed) and
// shared by the axes; each axis has instances of its own, so the model must allow several
// instances (canBeInstantiatedOnlyOncePerProcess = false) for more than one axis.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "plant/plant_catalog.hpp"

namespace netmc::plant::fmu {

// True when a plant name selects an FMU ("fmu:...").
bool is_fmu_plant(std::string_view plant_name);

// One FmuAxisPlant per axis (1..3), each probed once (instantiated, initialised with the FMU's
// own start values, freed): the plants start where the FMU's start values put them, and hold an
// instance from their first reset() or advance(). `text` is what follows "fmu:" (the prefix is
// taken too). overrides[i].parameters are Real parameters of axis i, set after the option-level
// ones; a non-zero disturbance is refused (not supported for FMUs). Throws std::invalid_argument
// naming the FMU and what is wrong (the archive, its description, a variable, an option), and
// std::runtime_error when an FMU call of the probe fails.
AxisSet make_fmu_plant_set(std::string_view text, std::size_t axis_count,
                           const std::vector<AxisOverrides>& overrides = {});

// What an FMU offers, from its modelDescription.xml alone (nothing is unpacked or loaded): for
// the catalog's plant_parameters() and plant_input_unit() of an fmu: name.
struct FmuPlantSummary {
  std::string model_name;
  std::string input_unit;                  // the input's Real unit attribute, "" when it has none
  std::vector<PlantParameter> parameters;  // its Real parameters, with their start values
};
FmuPlantSummary summarize_fmu_plant(std::string_view text);

}  // namespace netmc::plant::fmu
