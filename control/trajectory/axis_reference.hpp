#pragma once
// One axis's desired motion at an instant: what a single-axis reference gives and a tracking
// controller follows (thesis, paper 000, ch. 5).

namespace netmc::control {

struct AxisReference {
  double position = 0.0;      // x_d (m)
  double velocity = 0.0;      // x_d' (m/s)
  double acceleration = 0.0;  // x_d'' (m/s^2)
};

}  // namespace netmc::control
