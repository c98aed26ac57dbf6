#pragma once
// Paper 004, eq. 1: decoupled stage axis with high-frequency resonances,
//   P(s) = 1/(m s^2) + sum_i K_i / (s^2 + 4 pi x_i f_i s + (2 pi f_i)^2),
// input force F in N (d(t) adds to it, in N). Realised as a rigid body x'' = F/m plus one
// second-order modal state per resonance, q_i'' + 2 x_i w_i q_i' + w_i^2 q_i = K_i F
// (w_i = 2 pi f_i); position = x + sum_i q_i, velocity = x' + sum_i q_i'.
// The blocks are decoupled, so each is integrated on its own: exactly (matrix exponential) when d
// is constant over the step, otherwise RK4 with sub-steps no longer than max_substep_s.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "plant/disturbance.hpp"
#include "plant/exact_discretizer.hpp"
#include "plant/piecewise_axis_plant.hpp"

namespace netmc::plant {

struct ResonanceMode {
  double gain = 0, damping_ratio = 0, frequency_hz = 0;  // K_i (m/(N s^2)), x_i, f_i (Hz)
};

struct ResonantStageParameters {
  double mass = 24;  // m (kg)
  std::vector<ResonanceMode> modes;
  Disturbance disturbance;      // N
  double max_substep_s = 1e-5;  // RK4 sub-step bound (netmc's choice [A]: 100 kHz)
};

class ResonantStageAxis final : public PiecewiseAxisPlant {
 public:
  explicit ResonantStageAxis(ResonantStageParameters p);

  double position() const override;
  double velocity() const override;
  std::unique_ptr<AxisPlant> clone() const override;
  std::string describe() const override;

  const ResonantStageParameters& parameters() const { return p_; }
  // Rigid-body part [x, x'] and modal part [q_i, q_i'] of the state.
  const Eigen::Vector2d& rigid_state() const { return rigid_; }
  const Eigen::Vector2d& mode_state(std::size_t i) const { return modes_.at(i).z; }

 private:
  struct ModeState {
    double gain = 0.0;       // K_i
    double stiffness = 0.0;  // w_i^2
    double damping = 0.0;    // 2 x_i w_i
    ExactDiscretizer exact;
    Eigen::Vector2d z = Eigen::Vector2d::Zero();
  };

  const Disturbance& disturbance() const override { return p_.disturbance; }
  void reset_state(double position, double velocity) override;
  void advance_piece(double t0, double duration, double input, double step_level) override;

  ResonantStageParameters p_;
  Eigen::Vector2d rigid_ = Eigen::Vector2d::Zero();
  std::vector<ModeState> modes_;
};

}  // namespace netmc::plant
