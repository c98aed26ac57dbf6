#include "plant/position_sensor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "netsim/random_stream.hpp"

namespace netmc::plant {
namespace {

TEST(PositionSensor, OffMeansExact) {
  PositionSensor sensor({}, 1, 0);
  for (double y : {0.0, 1.234567890123, -0.5e-9}) EXPECT_EQ(sensor.measure(y), y);
}

TEST(PositionSensor, QuantisesToNearestMultipleOfResolution) {
  const double res = 0.5e-6;  // paper 000 encoder
  PositionSensor sensor({res, 0.0}, 7, 0);
  netsim::RandomStream positions(99);
  for (int i = 0; i < 10000; ++i) {
    const double y = positions.uniform(-0.3, 0.3);
    const double m = sensor.measure(y);
    const double counts = m / res;
    ASSERT_NEAR(counts, std::round(counts), 1e-6) << y;
    ASSERT_LE(std::abs(m - y), 0.5 * res * (1.0 + 1e-9)) << y;
  }
  EXPECT_EQ(sensor.measure(0.74e-6), 0.5e-6);
  EXPECT_EQ(sensor.measure(0.76e-6), 1.0e-6);
  EXPECT_EQ(sensor.measure(-0.24e-6), 0.0);
}

TEST(PositionSensor, NoiseHasTheRequestedStandardDeviation) {
  const double sigma = 2e-6, y0 = 0.0123;
  PositionSensor sensor({0.0, sigma}, 42, 3);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double e = sensor.measure(y0) - y0;
    sum += e;
    sum2 += e * e;
  }
  const double mean = sum / n;
  const double sd = std::sqrt(sum2 / n - mean * mean);
  // Five standard errors: sigma/sqrt(n) for the mean, sigma/sqrt(2n) for the deviation.
  EXPECT_LT(std::abs(mean), 5.0 * sigma / std::sqrt(n));
  EXPECT_LT(std::abs(sd / sigma - 1.0), 5.0 / std::sqrt(2.0 * n));
}

TEST(PositionSensor, NoiseThenQuantisation) {
  const double res = 1e-6;
  PositionSensor sensor({res, 3e-6}, 5, 0);
  bool varied = false;
  double first = sensor.measure(0.01);
  for (int i = 0; i < 1000; ++i) {
    const double m = sensor.measure(0.01);
    ASSERT_NEAR(m / res, std::round(m / res), 1e-6);
    varied = varied || m != first;
  }
  EXPECT_TRUE(varied);
}

TEST(PositionSensor, ResetRestartsTheStreamAndSeedsSeparateStreams) {
  PositionSensor a({0.0, 1e-6}, 11, 0);
  PositionSensor same({0.0, 1e-6}, 11, 0);
  PositionSensor other_stream({0.0, 1e-6}, 11, 1);
  std::vector<double> first;
  for (int i = 0; i < 20; ++i) first.push_back(a.measure(0.0));
  a.reset();
  int differs = 0;
  for (int i = 0; i < 20; ++i) {
    const double m = a.measure(0.0);
    EXPECT_EQ(m, first[static_cast<std::size_t>(i)]);
    EXPECT_EQ(same.measure(0.0), m);
    if (other_stream.measure(0.0) != m) ++differs;
  }
  EXPECT_EQ(differs, 20);
}

TEST(PositionSensor, RejectsBadParameters) {
  for (auto [p, name] : {std::pair{PositionSensorParameters{-1e-6, 0.0}, "resolution_m"},
                         std::pair{PositionSensorParameters{std::nan(""), 0.0}, "resolution_m"},
                         std::pair{PositionSensorParameters{0.0, -1.0}, "noise_stddev_m"},
                         std::pair{PositionSensorParameters{0.0, INFINITY}, "noise_stddev_m"}}) {
    try {
      PositionSensor sensor(p, 1, 0);
      ADD_FAILURE() << "no throw for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace netmc::plant
