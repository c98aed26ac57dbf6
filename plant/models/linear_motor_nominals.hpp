#pragma once
// The thesis's rigid linear-motor axes (linmotor.cpp), which linmotor-flex builds on.

#include <cstddef>
#include <vector>

#include "plant/linear_motor_axis.hpp"
#include "plant/plant_settings.hpp"

namespace netmc::plant {

// Paper 000, appendix A nominals of axis 0 (X) or 1 (Y; a third axis too).
LinearMotorParameters linmotor_axis_parameters(std::size_t axis);
std::vector<PlantSetting<LinearMotorParameters>> linmotor_settings();

}  // namespace netmc::plant
