#pragma once
// Skeleton shared by the plants driven by an additive Disturbance: advance() splits each held-input
// interval where the disturbance step switches (for_each_smooth_piece), so a plant only integrates
// smooth pieces and no integrator crosses the discontinuity. The plants supply the pieces.

#include <Eigen/Core>
#include <string_view>

#include "plant/axis_plant.hpp"
#include "plant/disturbance.hpp"

namespace netmc::plant {

class PiecewiseAxisPlant : public AxisPlant {
 public:
  // Validates, restarts the clock, then reset_state().
  void reset(double position, double velocity) final;
  // Validates, then advance_piece() per smooth piece of the disturbance.
  void advance(double duration_s, double input) final;
  double time() const final { return time_; }

 protected:
  // owner: the plant's name in error messages; must outlive the plant (a string literal).
  explicit PiecewiseAxisPlant(std::string_view owner) : owner_(owner) {}
  PiecewiseAxisPlant(const PiecewiseAxisPlant&) = default;
  PiecewiseAxisPlant& operator=(const PiecewiseAxisPlant&) = default;
  PiecewiseAxisPlant(PiecewiseAxisPlant&&) = default;
  PiecewiseAxisPlant& operator=(PiecewiseAxisPlant&&) = default;

 private:
  virtual const Disturbance& disturbance() const = 0;
  // Called with finite values; sets every state for t = 0.
  virtual void reset_state(double position, double velocity) = 0;
  // Integrates [t0, t0 + duration) with the input held and the disturbance step at step_level.
  virtual void advance_piece(double t0, double duration, double input, double step_level) = 0;

  std::string_view owner_;
  double time_ = 0.0;
};

// A plant whose whole state is [position, velocity].
class TwoStateAxisPlant : public PiecewiseAxisPlant {
 public:
  double position() const final { return z_(0); }
  double velocity() const final { return z_(1); }

 protected:
  using PiecewiseAxisPlant::PiecewiseAxisPlant;
  // [x, x'], for the plant's integrators.
  Eigen::Vector2d& state() { return z_; }

 private:
  void reset_state(double position, double velocity) final { z_ << position, velocity; }

  Eigen::Vector2d z_ = Eigen::Vector2d::Zero();
};

}  // namespace netmc::plant
