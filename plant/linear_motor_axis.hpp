#pragma once
// Thesis (paper 000) linear-motor axis, eq. 2-43 / 4-1 with the appendix A.1-A.3 friction:
//   M y'' = u - B y' - Ff(y') - Fr(y) + d(t),
// all forces in volts of drive command (the thesis identifies M in V/(m/s^2), B in V/(m/s)).
//   Ff(v) = (coulomb + stribeck_extra exp(-(v/stribeck_velocity)^2)) tanh(v/friction_smoothing)
//     (eq. A.3 with xi = 2, sgn smoothed by tanh so RK4 stays well behaved),
//   Fr(y) = sum_i S_i sin(2 pi i y / P) + C_i cos(2 pi i y / P)   (eq. 4-2, magnet pitch P).
// Exact (matrix exponential) when friction and cogging are off and d is constant over the step;
// otherwise RK4 with sub-steps no longer than max_substep_s.

#include <memory>
#include <string>
#include <vector>

#include "plant/disturbance.hpp"
#include "plant/exact_discretizer.hpp"
#include "plant/piecewise_axis_plant.hpp"

namespace netmc::plant {

struct CoggingHarmonic {
  double sine = 0, cosine = 0;  // S_i, C_i (V)
  int order = 1;                // harmonic i >= 1 of the magnet pitch
};

struct LinearMotorParameters {
  double mass = 0.12, damping = 0.3;          // M in V/(m/s^2), B in V/(m/s)
  double coulomb = 0.1;                       // A (V)
  double stribeck_extra = 0.0;                // fs - fc (V), >= 0
  double stribeck_velocity = 0.01;            // y'_s (m/s)
  double friction_smoothing_velocity = 1e-4;  // m/s, tanh smoothing of sgn(y')
  // Paper 000, section 4.4.1: measured magnet pitch P = 50 mm.
  double cogging_pitch_m = 0.05;
  std::vector<CoggingHarmonic> cogging;
  Disturbance disturbance;      // V
  double max_substep_s = 2e-5;  // RK4 sub-step bound
};

class LinearMotorAxis final : public TwoStateAxisPlant {
 public:
  explicit LinearMotorAxis(LinearMotorParameters p);

  std::unique_ptr<AxisPlant> clone() const override;
  std::string describe() const override;

  const LinearMotorParameters& parameters() const { return p_; }
  // Ff(v) and Fr(y) as above (V), exposed for tests and for compensator studies.
  double friction_force(double velocity) const;
  double cogging_force(double position) const;

 private:
  const Disturbance& disturbance() const override { return p_.disturbance; }
  void advance_piece(double t0, double duration, double input, double step_level) override;

  LinearMotorParameters p_;
  std::vector<double> wavenumbers_;  // 2 pi i / P per harmonic, rad/m
  bool linear_ = false;
  ExactDiscretizer exact_;
};

}  // namespace netmc::plant
