#pragma once
// Thesis (paper 000) linear-motor axis with the imperfections appendix A identifies beyond the
// rigid model of LinearMotorAxis (appendix A.2; levels the thesis does not give are netmc's [A]):
//   drive current loop, first order (A: bandwidth about 1.5 kHz):
//     tau f' = u + d - f,                               tau = 1 / (2 pi current_loop_hz)
//   two masses, the motor (coil, bearings, magnets' cogging) and the encoder's carriage:
//     M_m x_m'' = f - B x_m' - Ff(x_m') - Fr(x_m) - k (x_m - x_l) - c (x_m' - x_l')
//     M_l x_l'' = k (x_m - x_l) + c (x_m' - x_l')
//   with M_l = load_fraction M, M_m = M - M_l, and k, c chosen so the relative motion
//   q = x_m - x_l is the flexible mode of appendix A:
//     q'' + 2 zeta w q' + w^2 q = (motor-side force) / M_m,  w = 2 pi mode_frequency_hz,
//   i.e. k = w^2 M_m M_l / M, c = 2 zeta w M_m M_l / M. Below the mode the axis is the rigid
//   M y'' = u - B y' - Ff - Fr (A.1/A.2) of LinearMotorAxis.
// Ff (Stribeck per A.3, tanh-smoothed) and Fr (cogging, 4-2) are LinearMotorAxis's, from
// `motor`. The encoder reads the carriage: position() and velocity() are x_l and x_l'.
// The additive disturbance d (V) enters with the command, ahead of the drive (thesis ch. 3
// Set3 adds its step "to the Y input"). Forces in volts of drive command, as LinearMotorAxis.
// Integrated by RK4 with sub-steps no longer than max_substep_s (plant/models/linmotor_flex.cpp
// gives the bound).

#include <array>
#include <memory>
#include <string>

#include "plant/disturbance.hpp"
#include "plant/linear_motor_axis.hpp"
#include "plant/piecewise_axis_plant.hpp"

namespace netmc::plant {

struct FlexibleLinearMotorParameters {
  // Total mass M, B, friction and cogging; motor.disturbance and motor.max_substep_s are unused.
  LinearMotorParameters motor;
  double load_fraction = 0.3;         // M_l / M, the carriage's share of the mass, in (0, 1)
  double mode_frequency_hz = 150.0;   // f of the flexible mode (A: X 100-200 Hz, Y 40-80 Hz)
  double mode_damping_ratio = 0.05;   // zeta of the flexible mode
  double current_loop_hz = 1500.0;    // drive current-loop bandwidth (A: about 1.5 kHz)
  Disturbance disturbance;            // V, added to the command
  double max_substep_s = 2e-5;        // RK4 sub-step bound
};

class FlexibleLinearMotorAxis final : public PiecewiseAxisPlant {
 public:
  explicit FlexibleLinearMotorAxis(FlexibleLinearMotorParameters p);

  double position() const override { return z_[kLoadPosition]; }
  double velocity() const override { return z_[kLoadVelocity]; }
  std::unique_ptr<AxisPlant> clone() const override;
  std::string describe() const override;

  const FlexibleLinearMotorParameters& parameters() const { return p_; }
  // The motor side and the drive's force (V), for tests and studies of the mode.
  double motor_position() const { return z_[kMotorPosition]; }
  double motor_velocity() const { return z_[kMotorVelocity]; }
  double drive_force() const { return z_[kDriveForce]; }
  double motor_mass() const { return motor_mass_; }
  double load_mass() const { return load_mass_; }
  double stiffness() const { return stiffness_; }    // k (V/m)
  double mode_damping() const { return coupling_damping_; }  // c (V/(m/s))

 private:
  enum Index { kMotorPosition, kMotorVelocity, kLoadPosition, kLoadVelocity, kDriveForce, kSize };
  using State = std::array<double, kSize>;

  const Disturbance& disturbance() const override { return p_.disturbance; }
  void reset_state(double position, double velocity) override;
  void advance_piece(double t0, double duration, double input, double step_level) override;
  State derivative(const State& z, double command) const;

  FlexibleLinearMotorParameters p_;
  LinearMotorAxis rigid_;  // Ff and Fr of the motor side
  double motor_mass_ = 0.0, load_mass_ = 0.0;
  double stiffness_ = 0.0, coupling_damping_ = 0.0;
  double current_loop_rate_ = 0.0;  // 1 / tau (1/s)
  State z_{};
};

}  // namespace netmc::plant
