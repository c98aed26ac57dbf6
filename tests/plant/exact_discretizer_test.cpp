#include "plant/exact_discretizer.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace netmc::plant {
namespace {

TEST(ExactDiscretizer, DoubleIntegratorIsTheKinematicFormula) {
  Eigen::Matrix2d a;
  a << 0.0, 1.0, 0.0, 0.0;
  ExactDiscretizer zoh(a, Eigen::Vector2d(0.0, 1.0));
  const double h = 0.37;
  const auto& tr = zoh.transition(h);
  EXPECT_NEAR(tr.phi(0, 0), 1.0, 1e-15);
  EXPECT_NEAR(tr.phi(0, 1), h, 1e-15);
  EXPECT_NEAR(tr.phi(1, 0), 0.0, 1e-15);
  EXPECT_NEAR(tr.phi(1, 1), 1.0, 1e-15);
  EXPECT_NEAR(tr.gamma(0), h * h / 2.0, 1e-15);
  EXPECT_NEAR(tr.gamma(1), h, 1e-15);
}

TEST(ExactDiscretizer, HarmonicOscillatorRotates) {
  const double w = 3.0, h = 0.4;
  Eigen::Matrix2d a;
  a << 0.0, 1.0, -w * w, 0.0;
  ExactDiscretizer zoh(a, Eigen::Vector2d(0.0, 1.0));
  const auto& tr = zoh.transition(h);
  EXPECT_NEAR(tr.phi(0, 0), std::cos(w * h), 1e-14);
  EXPECT_NEAR(tr.phi(0, 1), std::sin(w * h) / w, 1e-14);
  EXPECT_NEAR(tr.phi(1, 0), -w * std::sin(w * h), 1e-14);
  EXPECT_NEAR(tr.gamma(0), (1.0 - std::cos(w * h)) / (w * w), 1e-14);
  EXPECT_NEAR(tr.gamma(1), std::sin(w * h) / w, 1e-14);
}

TEST(ExactDiscretizer, CachesPerDurationWithLeastRecentlyUsedEviction) {
  Eigen::Matrix2d a;
  a << 0.0, 1.0, 0.0, -20.0;
  ExactDiscretizer zoh(a, Eigen::Vector2d(0.0, 1.0));
  zoh.transition(5e-3);
  zoh.transition(5e-3);
  EXPECT_EQ(zoh.miss_count(), 1u);
  // A stream of one-off durations (random delays) never evicts the period used every cycle.
  for (int k = 0; k < 50; ++k) {
    zoh.transition(1e-4 * (k + 1) + 1e-9);
    zoh.transition(5e-3);
  }
  EXPECT_EQ(zoh.miss_count(), 51u);
  EXPECT_EQ(zoh.cached_count(), ExactDiscretizer::kCacheSize);
  // Cached and fresh transitions are identical.
  ExactDiscretizer fresh(a, Eigen::Vector2d(0.0, 1.0));
  EXPECT_EQ(fresh.transition(5e-3).phi, zoh.transition(5e-3).phi);
  EXPECT_EQ(fresh.transition(5e-3).gamma, zoh.transition(5e-3).gamma);
}

TEST(ExactDiscretizer, ZeroDurationIsIdentity) {
  Eigen::Matrix2d a;
  a << 0.0, 1.0, -4.0, -1.0;
  ExactDiscretizer zoh(a, Eigen::Vector2d(0.0, 2.0));
  Eigen::Vector2d z(0.3, -0.2);
  zoh.step(z, 0.0, 5.0);
  EXPECT_EQ(z, Eigen::Vector2d(0.3, -0.2));
}

}  // namespace
}  // namespace netmc::plant
