#pragma once
// The nominal model of a named plant's axis as a model-based controller or a delay compensator
// may know it: x'' = a x' + b u - c tanh(x' / v_s), the source's nominal parameters without the
// job's overrides or disturbances (a lab's identified model of its machine, not the machine).

#include <cstddef>
#include <optional>
#include <string_view>

namespace netmc::plant {

struct NominalAxisModel {
  double damping_per_s = 0.0;             // a (1/s)
  double input_gain = 1.0;                // b ((m/s^2) per input unit)
  double coulomb_m_s2 = 0.0;              // c (m/s^2)
  double coulomb_velocity_scale_m_s = 1e-3;  // v_s (m/s)
};

// Axis `axis` (0 = X, 1 = Y, 2 = a third axis with Y's parameters) of the named plant (its
// PlantModel's nominal_model); unset for a plant whose nominal model is not of this form
// (linmotor's cogging, linmotor-flex's and stage004's modes, hiwin's dead zone) or is unknown (a
// plant read from a file).
std::optional<NominalAxisModel> nominal_axis_model(std::string_view plant_name, std::size_t axis);

}  // namespace netmc::plant
