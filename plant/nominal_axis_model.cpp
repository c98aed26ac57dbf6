#include "plant/nominal_axis_model.hpp"

#include "plant/ball_screw_drive.hpp"
#include "plant/plant_catalog.hpp"

namespace netmc::plant {

std::optional<NominalAxisModel> nominal_axis_model(std::string_view plant_name, std::size_t axis) {
  if (axis > 2) return std::nullopt;
  if (plant_name == "seed001") {
    // paper 001, eq. 3 with netmc's assumed parameters (plant_catalog.cpp); a1 = 0.
    const SecondOrderAxisParameters p = seed001_axis_parameters(axis);
    if (p.a1 != 0.0) return std::nullopt;
    return NominalAxisModel{p.a2, p.b, p.coulomb_acceleration, p.coulomb_velocity_scale};
  }
  if (plant_name == "ballscrew") {
    // paper 002, eq. 1: y'' = -(B/J) y' + (Ka Kt rg / J) u.
    const BallScrewParameters p;
    return NominalAxisModel{-p.damping / p.inertia, p.amplifier_gain * p.torque_constant * p.lead_m_per_rad / p.inertia,
                            0.0, 1e-3};
  }
  return std::nullopt;
}

}  // namespace netmc::plant
