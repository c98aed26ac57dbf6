#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "netsim/delay_model.hpp"
#include "netsim_test_support.hpp"

namespace netmc::netsim {
namespace {

using test::draw_delays;
using test::expect_invalid_argument;
using test::kSampleCount;

constexpr double kGoodDelay = 0.001;
constexpr double kBadDelay = 0.010;

// Constant per-state delays make the hidden state observable from the delay alone.
std::unique_ptr<DelayModel> make_observable_markov(double p_good_to_bad, double p_bad_to_good) {
  return make_markov_delay(make_constant_delay(kGoodDelay), make_constant_delay(kBadDelay), p_good_to_bad,
                           p_bad_to_good);
}

TEST(MarkovDelay, StationaryBadFractionAndBurstLengthMatchFormulas) {
  const double p_gb = 0.05;
  const double p_bg = 0.2;
  auto model = make_observable_markov(p_gb, p_bg);
  RandomStream rng(41);
  const auto delays = draw_delays(*model, rng, kSampleCount);

  int bad_packets = 0;
  int bursts = 0;
  bool previous_bad = false;
  for (const double delay : delays) {
    const bool bad = delay == kBadDelay;
    bad_packets += bad ? 1 : 0;
    bursts += (bad && !previous_bad) ? 1 : 0;
    previous_bad = bad;
  }
  const double n = kSampleCount;
  const double bad_fraction = p_gb / (p_gb + p_bg);
  // Correlated samples: variance of the fraction is inflated by (1 + lambda) / (1 - lambda),
  // lambda = 1 - p_gb - p_bg the chain's second eigenvalue.
  const double lambda = 1.0 - p_gb - p_bg;
  const double fraction_se = std::sqrt(bad_fraction * (1.0 - bad_fraction) / n * (1.0 + lambda) / (1.0 - lambda));
  EXPECT_NEAR(bad_packets / n, bad_fraction, 5.0 * fraction_se);

  // Burst lengths are geometric with mean 1/p_bg and stddev sqrt(1 - p_bg)/p_bg.
  const double mean_burst = static_cast<double>(bad_packets) / bursts;
  EXPECT_NEAR(mean_burst, 1.0 / p_bg, 5.0 * std::sqrt(1.0 - p_bg) / p_bg / std::sqrt(bursts));

  const double expected_mean = (1.0 - bad_fraction) * kGoodDelay + bad_fraction * kBadDelay;
  EXPECT_NEAR(model->mean_s(), expected_mean, 1e-15);
  EXPECT_NEAR(test::sample_moments(delays).mean, expected_mean, 5.0 * fraction_se * (kBadDelay - kGoodDelay));
}

TEST(MarkovDelay, StartsGoodAndResetRestoresInitialState) {
  auto model = make_observable_markov(0.3, 0.3);
  RandomStream rng(42);
  EXPECT_EQ(model->next_delay_s(rng), kGoodDelay);
  const auto first_run = draw_delays(*model, rng, 200);

  // Same stream position and state -> same continuation after reset.
  RandomStream replay(42);
  model->reset();
  EXPECT_EQ(model->next_delay_s(replay), kGoodDelay);
  EXPECT_EQ(draw_delays(*model, replay, 200), first_run);

  // A clone starts from the initial state even when the original is mid-burst.
  RandomStream clone_rng(42);
  auto clone = model->clone();
  EXPECT_EQ(clone->next_delay_s(clone_rng), kGoodDelay);
  EXPECT_EQ(draw_delays(*clone, clone_rng, 200), first_run);
}

TEST(MarkovDelay, NeverSwitchingStaysGood) {
  auto model = make_observable_markov(0.0, 0.0);
  RandomStream rng(43);
  for (const double delay : draw_delays(*model, rng, 1000)) EXPECT_EQ(delay, kGoodDelay);
  EXPECT_EQ(model->mean_s(), kGoodDelay);
}

TEST(MarkovDelay, StateModelsDrawFromTheSharedStream) {
  auto model = make_markov_delay(make_uniform_delay(0.001, 0.002), make_uniform_delay(0.02, 0.03), 0.1, 0.5);
  RandomStream rng(44);
  for (const double delay : draw_delays(*model, rng, 10000)) {
    EXPECT_TRUE((delay >= 0.001 && delay <= 0.002) || (delay >= 0.02 && delay <= 0.03)) << delay;
  }
  EXPECT_NE(model->describe().find("good uniform(1 ms, 2 ms)"), std::string::npos) << model->describe();
}

TEST(MarkovDelay, RejectsBadParameters) {
  expect_invalid_argument([] { make_observable_markov(1.5, 0.1); }, {"markov delay", "p_good_to_bad", "[0, 1]", "1.5"});
  expect_invalid_argument([] { make_observable_markov(0.1, -0.1); }, {"markov delay", "p_bad_to_good"});
  expect_invalid_argument([] { make_markov_delay(nullptr, make_no_delay(), 0.1, 0.1); }, {"markov delay", "good"});
  expect_invalid_argument([] { make_markov_delay(make_no_delay(), nullptr, 0.1, 0.1); }, {"markov delay", "bad"});
}

}  // namespace
}  // namespace netmc::netsim
