#pragma once
// The drive tests' plant: x'' = -20 x' + 20 u, paper 001's speed-mode servo without friction,
// whose speed follows u with a 50 ms time constant (closed forms in each test).
#include <memory>

#include "plant/second_order_axis.hpp"

namespace netmc::drive {

inline std::unique_ptr<plant::AxisPlant> linear_servo_plant() {
  plant::SecondOrderAxisParameters p;
  p.a1 = 0.0;
  p.a2 = -20.0;
  p.b = 20.0;
  return std::make_unique<plant::SecondOrderAxis>(p);
}

}  // namespace netmc::drive
