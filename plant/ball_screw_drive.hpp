#pragma once
// Paper 002, eq. 1: ball-screw axis y = Ka Kt rg / (J s^2 + B s) (u + d), i.e.
//   y'' = -(B/J) y' + (Ka Kt rg / J) (u + d(t)),
// u in volts, y in m (rg in m/rad), d(t) in volts at the amplifier input. Exact (matrix
// exponential) when d is constant over the step, otherwise RK4 sub-steps.

#include <memory>
#include <string>

#include "plant/disturbance.hpp"
#include "plant/exact_discretizer.hpp"
#include "plant/piecewise_axis_plant.hpp"

namespace netmc::plant {

struct BallScrewParameters {
  double inertia = 0.8e-3;        // J, kg m^2
  double damping = 0.255;         // B, N m s/rad
  double amplifier_gain = 3.2;    // Ka, A/V
  double torque_constant = 0.9;   // Kt, N m/A
  double lead_m_per_rad = 0.005;  // rg, m/rad
  Disturbance disturbance;        // V
  double max_substep_s = 1e-4;    // RK4 sub-step bound
};

class BallScrewDrive final : public TwoStateAxisPlant {
 public:
  explicit BallScrewDrive(BallScrewParameters p);

  std::unique_ptr<AxisPlant> clone() const override;
  std::string describe() const override;

  const BallScrewParameters& parameters() const { return p_; }
  // Ka Kt rg / J, (m/s^2)/V.
  double input_gain() const { return gain_; }
  // B / J, 1/s.
  double damping_rate() const { return rate_; }

 private:
  const Disturbance& disturbance() const override { return p_.disturbance; }
  void advance_piece(double t0, double duration, double input, double step_level) override;

  BallScrewParameters p_;
  double gain_ = 0.0;
  double rate_ = 0.0;
  ExactDiscretizer exact_;
};

}  // namespace netmc::plant
