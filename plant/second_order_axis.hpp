#pragma once
// Paper 001, eq. 3: one servo axis in speed mode,
//   x'' = a1 x + a2 x' + b u + d(t) - coulomb * tanh(x' / coulomb_velocity_scale),
// with a Coulomb-like friction netmc assumes [A]. d(t) enters as an acceleration (m/s^2).
// Linear pieces (no friction, d constant over the piece) are integrated exactly by the matrix
// exponential; otherwise sub-steps no longer than max_substep_s: fifth-order Taylor steps
// (coulomb_taylor_step.hpp) where d is constant over the piece and the step is within their
// reach, classical RK4 elsewhere.

#include <memory>
#include <string>

#include "plant/disturbance.hpp"
#include "plant/exact_discretizer.hpp"
#include "plant/piecewise_axis_plant.hpp"

namespace netmc::plant {

struct SecondOrderAxisParameters {
  double a1 = 0, a2 = -20, b = 20;       // 1/s^2, 1/s, (m/s^2) per input unit
  double coulomb_acceleration = 0;       // m/s^2, >= 0
  double coulomb_velocity_scale = 5e-5;  // m/s, > 0: tanh smoothing of sgn(x')
  Disturbance disturbance;               // m/s^2
  double max_substep_s = 1e-4;           // RK4 sub-step bound, > 0
};

class SecondOrderAxis final : public TwoStateAxisPlant {
 public:
  explicit SecondOrderAxis(SecondOrderAxisParameters p);

  std::unique_ptr<AxisPlant> clone() const override;
  std::string describe() const override;

  const SecondOrderAxisParameters& parameters() const { return p_; }

 private:
  const Disturbance& disturbance() const override { return p_.disturbance; }
  void advance_piece(double t0, double duration, double input, double step_level) override;

  SecondOrderAxisParameters p_;
  ExactDiscretizer exact_;
};

}  // namespace netmc::plant
