#include "netsim/loss_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "netsim_test_support.hpp"

namespace netmc::netsim {
namespace {

using test::expect_invalid_argument;
using test::kSampleCount;

std::vector<bool> draw_drops(LossModel& model, RandomStream& rng, int count) {
  std::vector<bool> drops;
  for (int i = 0; i < count; ++i) drops.push_back(model.drop(rng));
  return drops;
}

double drop_fraction(const std::vector<bool>& drops) {
  int dropped = 0;
  for (const bool d : drops) dropped += d ? 1 : 0;
  return static_cast<double>(dropped) / static_cast<double>(drops.size());
}

TEST(NoLoss, NeverDrops) {
  auto model = make_no_loss();
  RandomStream rng(1);
  EXPECT_EQ(drop_fraction(draw_drops(*model, rng, 1000)), 0.0);
  EXPECT_EQ(model->mean_loss_rate(), 0.0);
  EXPECT_EQ(model->describe(), "no loss");
}

TEST(BernoulliLoss, RateMatchesProbability) {
  const double p = 0.1;
  auto model = make_bernoulli_loss(p);
  RandomStream rng(51);
  const double n = kSampleCount;
  EXPECT_NEAR(drop_fraction(draw_drops(*model, rng, kSampleCount)), p, 5.0 * std::sqrt(p * (1.0 - p) / n));
  EXPECT_EQ(model->mean_loss_rate(), p);
  EXPECT_EQ(model->describe(), "bernoulli(p 0.1)");
}

TEST(BernoulliLoss, ZeroAndOneAreExact) {
  RandomStream rng(52);
  EXPECT_EQ(drop_fraction(draw_drops(*make_bernoulli_loss(0.0), rng, 10000)), 0.0);
  EXPECT_EQ(drop_fraction(draw_drops(*make_bernoulli_loss(1.0), rng, 10000)), 1.0);
}

TEST(BernoulliLoss, SameSeedSameDecisions) {
  auto model = make_bernoulli_loss(0.5);
  RandomStream a(53, 4);
  RandomStream b(53, 4);
  RandomStream c(53, 5);
  const auto first = draw_drops(*model, a, 500);
  EXPECT_EQ(draw_drops(*model, b, 500), first);
  EXPECT_NE(draw_drops(*model, c, 500), first);
}

TEST(GilbertElliottLoss, RateMatchesStationaryFormula) {
  const double p_gb = 0.02;
  const double p_bg = 0.25;
  const double loss_good = 0.01;
  const double loss_bad = 0.5;
  auto model = make_gilbert_elliott_loss(p_gb, p_bg, loss_good, loss_bad);
  const int count = 2 * kSampleCount;
  RandomStream rng(54);
  const double bad_fraction = p_gb / (p_gb + p_bg);
  const double expected = (1.0 - bad_fraction) * loss_good + bad_fraction * loss_bad;
  // Per-packet variance plus the state's correlated contribution, summed over the chain's
  // geometric autocorrelation (lambda = 1 - p_gb - p_bg).
  const double lambda = 1.0 - p_gb - p_bg;
  const double state_variance = bad_fraction * (1.0 - bad_fraction) * (loss_bad - loss_good) * (loss_bad - loss_good);
  const double effective_variance = expected * (1.0 - expected) + state_variance * 2.0 * lambda / (1.0 - lambda);
  EXPECT_NEAR(drop_fraction(draw_drops(*model, rng, count)), expected,
              5.0 * std::sqrt(effective_variance / count));
  EXPECT_NEAR(model->mean_loss_rate(), expected, 1e-15);
}

TEST(GilbertElliottLoss, PureGilbertBurstsHaveMeanLength) {
  // Loss exactly in the bad state: loss runs are bad-state sojourns, mean length 1/p_bg.
  const double p_bg = 0.3;
  auto model = make_gilbert_elliott_loss(0.05, p_bg, 0.0, 1.0);
  RandomStream rng(55);
  const auto drops = draw_drops(*model, rng, kSampleCount);
  EXPECT_FALSE(drops.front());  // starts in the good state
  int lost = 0;
  int bursts = 0;
  bool previous = false;
  for (const bool d : drops) {
    lost += d ? 1 : 0;
    bursts += (d && !previous) ? 1 : 0;
    previous = d;
  }
  EXPECT_NEAR(static_cast<double>(lost) / bursts, 1.0 / p_bg, 5.0 * std::sqrt(1.0 - p_bg) / p_bg / std::sqrt(bursts));
}

TEST(GilbertElliottLoss, ResetAndCloneReplay) {
  auto model = make_gilbert_elliott_loss(0.2, 0.2, 0.0, 1.0);
  RandomStream rng(56);
  const auto first = draw_drops(*model, rng, 300);
  model->reset();
  RandomStream replay(56);
  EXPECT_EQ(draw_drops(*model, replay, 300), first);
  auto clone = model->clone();
  RandomStream clone_rng(56);
  EXPECT_EQ(draw_drops(*clone, clone_rng, 300), first);
}

TEST(LossModel, RejectsProbabilitiesOutsideUnitInterval) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid_argument([] { make_bernoulli_loss(1.2); }, {"bernoulli loss", "p must be a probability in [0, 1]", "p=1.2"});
  expect_invalid_argument([] { make_bernoulli_loss(-0.1); }, {"bernoulli loss", "p=-0.1"});
  expect_invalid_argument([&] { make_bernoulli_loss(nan); }, {"bernoulli loss", "nan"});
  expect_invalid_argument([] { make_gilbert_elliott_loss(2.0, 0.1, 0.0, 1.0); }, {"gilbert-elliott loss", "p_good_to_bad"});
  expect_invalid_argument([] { make_gilbert_elliott_loss(0.1, -1.0, 0.0, 1.0); }, {"gilbert-elliott loss", "p_bad_to_good"});
  expect_invalid_argument([&] { make_gilbert_elliott_loss(0.1, 0.1, nan, 1.0); }, {"gilbert-elliott loss", "loss_in_good"});
  expect_invalid_argument([] { make_gilbert_elliott_loss(0.1, 0.1, 0.0, 1.5); }, {"gilbert-elliott loss", "loss_in_bad"});
}

}  // namespace
}  // namespace netmc::netsim
