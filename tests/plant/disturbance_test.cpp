#include "plant/disturbance.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace netmc::plant {
namespace {

TEST(Disturbance, ValueIsTheSumOfTheEnabledParts) {
  Disturbance d;
  EXPECT_TRUE(d.is_zero());
  EXPECT_EQ(d.value(3.0), 0.0);
  d.constant = 0.2;
  d.sine_amplitude = 0.5;
  d.sine_frequency_hz = 4.0;
  d.sine_phase_rad = 0.3;
  d.step_amplitude = -1.0;
  d.step_time_s = 2.2;
  EXPECT_FALSE(d.is_zero());
  for (double t : {0.0, 1.0, 2.1999, 2.2, 5.2}) {
    const double expected =
        0.2 + 0.5 * std::sin(2.0 * std::numbers::pi * 4.0 * t + 0.3) + (t >= 2.2 ? -1.0 : 0.0);
    EXPECT_NEAR(d.value(t), expected, 1e-15) << t;
  }
}

TEST(Disturbance, StepWithZeroAmplitudeIsOff) {
  Disturbance d;
  d.step_time_s = 1.0;
  EXPECT_TRUE(d.is_zero());
  EXPECT_EQ(d.value(2.0), 0.0);
}

TEST(Disturbance, SmoothPiecesSplitAtTheStep) {
  Disturbance d;
  d.step_amplitude = 0.8;
  d.step_time_s = 0.3;
  struct Piece {
    double t0, dt, level;
  };
  auto pieces = [&](double t0, double dt) {
    std::vector<Piece> out;
    for_each_smooth_piece(d, t0, dt, [&](double a, double b, double c) {
      out.push_back({a, b, c});
    });
    return out;
  };
  auto before = pieces(0.0, 0.1);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].level, 0.0);
  auto across = pieces(0.25, 0.1);
  ASSERT_EQ(across.size(), 2u);
  EXPECT_NEAR(across[0].dt, 0.05, 1e-15);
  EXPECT_EQ(across[0].level, 0.0);
  EXPECT_EQ(across[1].t0, 0.3);
  EXPECT_NEAR(across[1].dt, 0.05, 1e-15);
  EXPECT_EQ(across[1].level, 0.8);
  auto at = pieces(0.3, 0.1);  // active for t >= step_time
  ASSERT_EQ(at.size(), 1u);
  EXPECT_EQ(at[0].level, 0.8);
  // The step starts at the end (0.2 + 0.1 rounds to 0.30000000000000004): not in this interval,
  // and no sliver piece.
  auto ending = pieces(0.2, 0.1);
  ASSERT_EQ(ending.size(), 1u);
  EXPECT_EQ(ending[0].level, 0.0);
  // An interval starting a rounding error before the step counts as after it.
  auto rounded = pieces(0.3 - 1e-16, 0.1);
  ASSERT_EQ(rounded.size(), 1u);
  EXPECT_EQ(rounded[0].level, 0.8);
}

TEST(Disturbance, SmoothPartConstancy) {
  Disturbance d;
  d.constant = 1.0;
  EXPECT_TRUE(smooth_part_is_constant(d));
  d.sine_amplitude = 1.0;
  d.sine_phase_rad = std::numbers::pi / 2.0;
  EXPECT_TRUE(smooth_part_is_constant(d));  // frequency 0: a constant sin(phase)
  EXPECT_NEAR(smooth_part(d, 7.0), 2.0, 1e-15);
  d.sine_frequency_hz = 1.0;
  EXPECT_FALSE(smooth_part_is_constant(d));
}

TEST(Disturbance, ValidationNamesTheField) {
  Disturbance d;
  d.sine_frequency_hz = -1.0;
  try {
    validate_disturbance(d, "Owner");
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("Owner"), std::string::npos) << what;
    EXPECT_NE(what.find("disturbance.sine_frequency_hz"), std::string::npos) << what;
  }
  d = {};
  d.step_time_s = std::nan("");
  EXPECT_THROW(validate_disturbance(d, "Owner"), std::invalid_argument);
  EXPECT_EQ(describe_disturbance(Disturbance{}, "N"), "none");
  Disturbance c;
  c.constant = 0.5;
  EXPECT_EQ(describe_disturbance(c, "N"), "const 0.5 N");
}

}  // namespace
}  // namespace netmc::plant

namespace netmc::plant {
namespace {

TEST(Disturbance, StepSwitchesOffAtItsOffTime) {
  Disturbance d;
  d.step_amplitude = 0.8;
  d.step_time_s = 2.2;
  d.step_off_s = 5.2;
  EXPECT_EQ(d.value(2.1), 0.0);
  EXPECT_EQ(d.value(2.2), 0.8);
  EXPECT_EQ(d.value(5.19), 0.8);
  EXPECT_EQ(d.value(5.2), 0.0);
  // One interval across both switches: three pieces at the right levels.
  std::vector<std::array<double, 3>> pieces;
  for_each_smooth_piece(d, 2.0, 4.0, [&](double t0, double dt, double level) { pieces.push_back({t0, dt, level}); });
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0][2], 0.0);
  EXPECT_NEAR(pieces[1][0], 2.2, 1e-15);
  EXPECT_NEAR(pieces[1][1], 3.0, 1e-12);
  EXPECT_EQ(pieces[1][2], 0.8);
  EXPECT_NEAR(pieces[2][0], 5.2, 1e-15);
  EXPECT_EQ(pieces[2][2], 0.0);
  d.step_off_s = 2.0;  // off before on
  EXPECT_THROW(validate_disturbance(d, "test"), std::invalid_argument);
}

TEST(Disturbance, BandLimitedNoiseHasItsStddevAndNoPowerAboveItsBand) {
  Disturbance d;
  d.noise = make_band_limited_noise(0.5, 20.0, 42);
  EXPECT_FALSE(d.is_zero());
  EXPECT_FALSE(smooth_part_is_constant(d));
  // Variance over a long run against stddev^2; the same seed gives the same signal.
  const int n = 200000;
  const double dt = 1e-3;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double v = d.value(i * dt);
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n;
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), 0.5, 0.02);
  EXPECT_EQ(make_band_limited_noise(0.5, 20.0, 42).value(1.234), d.value(1.234));
  EXPECT_NE(make_band_limited_noise(0.5, 20.0, 43).value(1.234), d.value(1.234));
  // Band limit: every component lies in (0, 20 Hz].
  for (double w : d.noise.angular_frequency) {
    EXPECT_GT(w, 0.0);
    EXPECT_LE(w, 2.0 * std::numbers::pi * 20.0);
  }
  d.noise.bandwidth_hz = 0.0;
  EXPECT_THROW(validate_disturbance(d, "test"), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::plant
