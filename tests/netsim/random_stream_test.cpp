#include "netsim/random_stream.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "netsim_test_support.hpp"

namespace netmc::netsim {
namespace {

using test::kSampleCount;
using test::sample_moments;

TEST(RandomStream, SameSeedAndStreamGiveIdenticalSequence) {
  RandomStream a(42, 3);
  RandomStream b(42, 3);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.next_u64(), b.next_u64()) << "draw " << i;
}

TEST(RandomStream, DifferentStreamOrSeedGivesDifferentSequence) {
  RandomStream base(42, 0);
  RandomStream other_stream(42, 1);
  RandomStream other_seed(43, 0);
  int equal_to_other_stream = 0;
  int equal_to_other_seed = 0;
  for (int i = 0; i < 1000; ++i) {
    const std::uint64_t value = base.next_u64();
    equal_to_other_stream += value == other_stream.next_u64() ? 1 : 0;
    equal_to_other_seed += value == other_seed.next_u64() ? 1 : 0;
  }
  EXPECT_EQ(equal_to_other_stream, 0);
  EXPECT_EQ(equal_to_other_seed, 0);
}

TEST(RandomStream, UniformHasUnitIntervalMoments) {
  RandomStream rng(7);
  std::vector<double> samples;
  for (int i = 0; i < kSampleCount; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    samples.push_back(u);
  }
  const auto moments = sample_moments(samples);
  const double n = kSampleCount;
  // Var(U) = 1/12; Var(s^2) ~ (mu4 - sigma^4)/n with mu4 = 1/80.
  EXPECT_NEAR(moments.mean, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(moments.variance, 1.0 / 12.0, 5.0 * std::sqrt((1.0 / 80.0 - 1.0 / 144.0) / n));
}

TEST(RandomStream, UniformOnIntervalStaysInsideAndCentres) {
  RandomStream rng(8);
  double sum = 0.0;
  for (int i = 0; i < kSampleCount; ++i) {
    const double x = rng.uniform(-2.0, 6.0);
    ASSERT_GE(x, -2.0);
    ASSERT_LE(x, 6.0);
    sum += x;
  }
  EXPECT_NEAR(sum / kSampleCount, 2.0, 5.0 * 8.0 / std::sqrt(12.0 * kSampleCount));
}

TEST(RandomStream, StandardNormalHasZeroMeanUnitVariance) {
  RandomStream rng(9);
  std::vector<double> samples;
  for (int i = 0; i < kSampleCount; ++i) samples.push_back(rng.standard_normal());
  const auto moments = sample_moments(samples);
  const double n = kSampleCount;
  EXPECT_NEAR(moments.mean, 0.0, 5.0 / std::sqrt(n));
  EXPECT_NEAR(moments.variance, 1.0, 5.0 * std::sqrt(2.0 / n));  // Var(s^2) = 2 sigma^4 / n
  int beyond_two_sigma = 0;
  for (const double x : samples) beyond_two_sigma += std::abs(x) > 2.0 ? 1 : 0;
  const double p_beyond = 2.0 * (1.0 - test::normal_cdf(2.0));
  EXPECT_NEAR(beyond_two_sigma / n, p_beyond, 5.0 * std::sqrt(p_beyond * (1.0 - p_beyond) / n));
}

}  // namespace
}  // namespace netmc::netsim
