#pragma once
// An unknown input dead zone in front of an axis (thesis, paper 000, eq. 5-2):
//   w = m_r (v - b_r) for v >= b_r,  0 for b_l < v < b_r,  m_l (v - b_l) for v <= b_l,
// where v is the command and w what reaches the wrapped plant. The dead zone is static, so a held
// v is a held w and the wrapped plant integrates the piece as usual.

#include <memory>
#include <string>

#include "plant/axis_plant.hpp"

namespace netmc::plant {

struct DeadZoneParameters {
  double right_break_v = 0.0;  // b_r (input units), >= 0
  double left_break_v = 0.0;   // b_l (input units), <= 0
  double right_slope = 1.0;    // m_r, > 0
  double left_slope = 1.0;     // m_l, > 0
};

// Throws std::invalid_argument naming the field unless every field is finite, b_l <= 0 <= b_r and
// both slopes are > 0.
void validate_dead_zone(const DeadZoneParameters& p);

// D(v) of eq. 5-2.
inline double dead_zone_output(const DeadZoneParameters& p, double v) {
  if (v >= p.right_break_v) return p.right_slope * (v - p.right_break_v);
  if (v <= p.left_break_v) return p.left_slope * (v - p.left_break_v);
  return 0.0;
}

class DeadZoneInput final : public AxisPlant {
 public:
  // `inner` must not be null.
  DeadZoneInput(DeadZoneParameters dead_zone, std::unique_ptr<AxisPlant> inner);

  void reset(double position, double velocity) override { inner_->reset(position, velocity); }
  void advance(double duration_s, double input) override;
  double position() const override { return inner_->position(); }
  double velocity() const override { return inner_->velocity(); }
  double time() const override { return inner_->time(); }
  std::unique_ptr<AxisPlant> clone() const override;
  std::string describe() const override;

  const DeadZoneParameters& dead_zone() const { return dead_zone_; }
  const AxisPlant& inner() const { return *inner_; }

 private:
  DeadZoneParameters dead_zone_;
  std::unique_ptr<AxisPlant> inner_;
};

}  // namespace netmc::plant
