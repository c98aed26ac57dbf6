// smooth_sign replaces std::tanh in the plants' friction: it must agree with libm to a few ulp
// over the whole line, be odd, exact at 0 and bounded by 1.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "plant/smooth_sign.hpp"

namespace netmc::plant {
namespace {

TEST(SmoothSign, AgreesWithLibmTanhToRoundOff) {
  double worst = 0.0;
  // Logarithmic sweep from 1e-300 to 1e3, both signs, with the branch points on it.
  for (double a = 1e-300; a < 1e3; a *= 1.0009) {
    for (const double x : {a, -a}) {
      const double expected = std::tanh(x);
      worst = std::max(worst, std::abs(smooth_sign(x) - expected) / std::abs(expected));
    }
  }
  for (const double x : {0.01, std::nextafter(0.01, 0.0), 20.0, std::nextafter(20.0, 0.0), 0.5, 3.0}) {
    worst = std::max(worst, std::abs(smooth_sign(x) - std::tanh(x)) / std::tanh(x));
  }
  EXPECT_LT(worst, 1e-14);
}

TEST(SmoothSign, IsOddBoundedAndExactAtZero) {
  EXPECT_EQ(smooth_sign(0.0), 0.0);
  for (const double x : {1e-12, 0.003, 0.7, 5.0, 19.9, 25.0, 1e300, std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(smooth_sign(-x), -smooth_sign(x));
    EXPECT_LE(std::abs(smooth_sign(x)), 1.0);
  }
  EXPECT_EQ(smooth_sign(std::numeric_limits<double>::infinity()), 1.0);
}

}  // namespace
}  // namespace netmc::plant
