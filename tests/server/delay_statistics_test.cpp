// The delays of an iteration in bounded memory: exact as the whole vector gave them up to
// kExactSamples, within the histogram's 0.05 % beyond, mean and max exact throughout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "server/sim/delay_statistics.hpp"

namespace netmc::sim {
namespace {

// The reference: the statistics of the whole vector (the rank the server always used).
double exact_percentile(std::vector<double> values, double fraction) {
  const auto rank = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size())));
  const std::size_t index = std::min(values.size() - 1, rank == 0 ? 0 : rank - 1);
  std::sort(values.begin(), values.end());
  return values[index];
}

TEST(DelayStatistics, FewSamplesGiveTheWholeVectorsNumbersBitForBit) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> delay(3e-4, 8e-4);
  DelayStatistics statistics;
  std::vector<double> values;
  for (int i = 0; i < 10001; ++i) {
    values.push_back(delay(random));
    statistics.add(values.back());
  }
  statistics.replace_last(0.5);
  values.back() = 0.5;
  double sum = 0.0;
  for (const double v : values) sum += v;
  EXPECT_FALSE(statistics.binned());
  EXPECT_EQ(statistics.mean(), sum / static_cast<double>(values.size()));
  EXPECT_EQ(statistics.max(), 0.5);
  EXPECT_EQ(statistics.percentile(0.5), exact_percentile(values, 0.5));
  EXPECT_EQ(statistics.percentile(0.99), exact_percentile(values, 0.99));
}

TEST(DelayStatistics, ManySamplesAreBinnedWithinTheirResolution) {
  std::mt19937_64 random(11);
  std::exponential_distribution<double> delay(1.0 / 2e-3);
  DelayStatistics statistics;
  std::vector<double> values;
  const std::size_t count = DelayStatistics::kExactSamples + 500000;
  values.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    values.push_back(i % 1000 == 0 ? 0.0 : delay(random) - 1e-4);  // zeros and some negatives too
    statistics.add(values.back());
  }
  ASSERT_TRUE(statistics.binned());
  EXPECT_EQ(statistics.size(), count);
  EXPECT_EQ(statistics.max(), *std::max_element(values.begin(), values.end()));
  double sum = 0.0;
  for (const double v : values) sum += v;
  EXPECT_NEAR(statistics.mean(), sum / static_cast<double>(count), 1e-12);
  for (const double fraction : {0.01, 0.5, 0.99}) {
    const double exact = exact_percentile(values, fraction);
    EXPECT_NEAR(statistics.percentile(fraction), exact, 5e-4 * std::abs(exact) + 1e-9) << fraction;
  }
  statistics.clear();
  EXPECT_FALSE(statistics.binned());
  EXPECT_EQ(statistics.percentile(0.5), 0.0);
}

// Reserved for an iteration's length beforehand (the axis node's loop allocates nothing while
// it runs): the same numbers as growing into them, bit for bit, binned from the first sample
// when the iteration is long.
TEST(DelayStatistics, ReservedForTheIterationGivesTheSameNumbersAsGrowing) {
  for (const std::size_t count : {std::size_t{10001}, DelayStatistics::kExactSamples + 1000}) {
    std::mt19937_64 random(13);
    std::exponential_distribution<double> delay(1.0 / 2e-3);
    DelayStatistics grown;
    DelayStatistics reserved;
    reserved.reserve_for(count);
    EXPECT_EQ(reserved.binned(), count > DelayStatistics::kExactSamples) << count;
    for (std::size_t i = 0; i < count; ++i) {
      const double value = delay(random) - 3e-3;  // negatives too: the maximum may be one
      grown.add(value);
      reserved.add(value);
    }
    ASSERT_EQ(reserved.binned(), grown.binned()) << count;
    EXPECT_EQ(reserved.size(), count);
    EXPECT_EQ(reserved.mean(), grown.mean()) << count;
    EXPECT_EQ(reserved.max(), grown.max()) << count;
    for (const double fraction : {0.01, 0.5, 0.99}) {
      EXPECT_EQ(reserved.percentile(fraction), grown.percentile(fraction)) << count << " " << fraction;
    }
  }
}

TEST(DelayStatistics, TheMaximumOfNegativeSamplesIsTheirOwn) {
  DelayStatistics statistics;
  statistics.reserve_for(DelayStatistics::kExactSamples + 1);  // binned
  for (const double value : {-3e-3, -1e-3, -2e-3}) statistics.add(value);
  EXPECT_EQ(statistics.max(), -1e-3);
}

}  // namespace
}  // namespace netmc::sim
