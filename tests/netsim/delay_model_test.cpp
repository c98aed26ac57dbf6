#include "netsim/delay_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "netsim_test_support.hpp"

namespace netmc::netsim {
namespace {

using test::draw_delays;
using test::expect_invalid_argument;
using test::kSampleCount;
using test::sample_moments;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(NoDelay, AlwaysZero) {
  auto model = make_no_delay();
  RandomStream rng(1);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(model->next_delay_s(rng), 0.0);
  EXPECT_EQ(model->mean_s(), 0.0);
  EXPECT_EQ(model->describe(), "no delay");
}

TEST(ConstantDelay, AlwaysTheGivenDelay) {
  auto model = make_constant_delay(0.0025);
  RandomStream rng(1);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(model->next_delay_s(rng), 0.0025);
  EXPECT_EQ(model->mean_s(), 0.0025);
  EXPECT_EQ(model->describe(), "constant(2.5 ms)");
  EXPECT_EQ(model->clone()->next_delay_s(rng), 0.0025);
}

TEST(ConstantDelay, RejectsNegativeAndNonFinite) {
  expect_invalid_argument([] { make_constant_delay(-0.001); }, {"constant delay", "delay", "in [0, 60] s", "-0.001"});
  expect_invalid_argument([] { make_constant_delay(kNaN); }, {"constant delay", "nan"});
  expect_invalid_argument([] { make_constant_delay(kInf); }, {"constant delay", "inf"});
  // A minute is the longest delay a parameter may state (a message this late is lost anyway).
  EXPECT_NO_THROW(make_constant_delay(60.0));
  expect_invalid_argument([] { make_constant_delay(60.5); }, {"constant delay", "in [0, 60] s", "60.5"});
}

TEST(UniformDelay, MeanAndVarianceMatchClosedForm) {
  const double a = 0.0003;
  const double b = 0.0008;
  auto model = make_uniform_delay(a, b);
  RandomStream rng(11);
  const auto samples = draw_delays(*model, rng, kSampleCount);
  for (const double x : samples) {
    ASSERT_GE(x, a);
    ASSERT_LE(x, b);
  }
  const auto moments = sample_moments(samples);
  const double n = kSampleCount;
  const double width = b - a;
  const double variance = width * width / 12.0;
  const double fourth_central_moment = std::pow(width, 4) / 80.0;
  EXPECT_NEAR(moments.mean, (a + b) / 2.0, 5.0 * std::sqrt(variance / n));
  EXPECT_NEAR(moments.variance, variance, 5.0 * std::sqrt((fourth_central_moment - variance * variance) / n));
  EXPECT_DOUBLE_EQ(model->mean_s(), (a + b) / 2.0);
  EXPECT_EQ(model->describe(), "uniform(0.3 ms, 0.8 ms)");
}

TEST(UniformDelay, EqualBoundsGiveConstant) {
  auto model = make_uniform_delay(0.001, 0.001);
  RandomStream rng(3);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(model->next_delay_s(rng), 0.001);
}

TEST(UniformDelay, RejectsBadBounds) {
  expect_invalid_argument([] { make_uniform_delay(0.002, 0.001); },
                          {"uniform delay: min must be <= max (got min=0.002 s, max=0.001 s)"});
  expect_invalid_argument([] { make_uniform_delay(-0.001, 0.001); }, {"uniform delay", "min", "in [0, 60] s"});
  expect_invalid_argument([] { make_uniform_delay(0.0, kNaN); }, {"uniform delay", "max", "nan"});
  expect_invalid_argument([] { make_uniform_delay(0.0, kInf); }, {"uniform delay", "max", "in [0, 60] s"});
}

TEST(UniformDelay, SameSeedSameSequenceDifferentStreamDifferent) {
  auto model = make_uniform_delay(0.0, 0.01);
  RandomStream first(5, 1);
  RandomStream again(5, 1);
  RandomStream other(5, 2);
  const auto a = draw_delays(*model, first, 100);
  const auto b = draw_delays(*model, again, 100);
  const auto c = draw_delays(*model, other, 100);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

// Closed-form mean of N(mu, sigma) truncated to [lo, hi], from the standard normal pdf/cdf.
double truncated_normal_mean(double mu, double sigma, double lo, double hi) {
  const double alpha = (lo - mu) / sigma;
  const double beta = (hi - mu) / sigma;
  return mu + sigma * (test::normal_pdf(alpha) - test::normal_pdf(beta)) /
                  (test::normal_cdf(beta) - test::normal_cdf(alpha));
}

TEST(TruncatedNormalDelay, StaysInBoundsAndMatchesTruncatedMean) {
  const double mu = 0.001;
  const double sigma = 0.0005;
  const double lo = 0.0005;
  const double hi = 0.002;
  auto model = make_truncated_normal_delay(mu, sigma, lo, hi);
  RandomStream rng(21);
  const auto samples = draw_delays(*model, rng, kSampleCount);
  for (const double x : samples) {
    ASSERT_GE(x, lo);
    ASSERT_LE(x, hi);
  }
  const double expected_mean = truncated_normal_mean(mu, sigma, lo, hi);
  // The truncated standard deviation is below sigma, so sigma gives a safe bound.
  EXPECT_NEAR(sample_moments(samples).mean, expected_mean, 5.0 * sigma / std::sqrt(kSampleCount));
  EXPECT_NEAR(model->mean_s(), expected_mean, 1e-12);
}

TEST(TruncatedNormalDelay, HalfNormalWithInfiniteMax) {
  const double sigma = 0.001;
  auto model = make_truncated_normal_delay(0.0, sigma, 0.0, kInf);
  RandomStream rng(22);
  const auto samples = draw_delays(*model, rng, kSampleCount);
  const double expected_mean = sigma * std::sqrt(2.0 / std::numbers::pi);  // half-normal mean
  EXPECT_NEAR(sample_moments(samples).mean, expected_mean, 5.0 * sigma / std::sqrt(kSampleCount));
  EXPECT_NEAR(model->mean_s(), expected_mean, 1e-12);
}

TEST(TruncatedNormalDelay, FarTailWindowIsClampedNotEndless) {
  // Window 20 sigma above the mean: rejection never succeeds, so draws are clamped to min.
  auto model = make_truncated_normal_delay(0.001, 0.0001, 0.003, 0.004);
  RandomStream rng(23);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(model->next_delay_s(rng), 0.003);
  EXPECT_GE(model->mean_s(), 0.003);
  EXPECT_LE(model->mean_s(), 0.004);
}

TEST(TruncatedNormalDelay, RejectsBadParameters) {
  expect_invalid_argument([] { make_truncated_normal_delay(0.001, -0.1, 0.0, 0.01); },
                          {"truncated normal delay", "stddev", "in [0, 60] s"});
  expect_invalid_argument([] { make_truncated_normal_delay(0.001, 0.001, 0.002, 0.001); },
                          {"truncated normal delay", "max", ">= min", "min=0.002 s", "max=0.001 s"});
  expect_invalid_argument([] { make_truncated_normal_delay(kNaN, 0.001, 0.0, 0.01); },
                          {"truncated normal delay", "mean", "nan"});
  expect_invalid_argument([] { make_truncated_normal_delay(0.001, 0.001, -0.001, 0.01); },
                          {"truncated normal delay", "min"});
}

TEST(ParetoDelay, UncappedMeanAndTailMatchClosedForm) {
  const double scale = 0.001;
  const double shape = 3.0;
  auto model = make_pareto_delay(scale, shape, kInf);
  RandomStream rng(31);
  const auto samples = draw_delays(*model, rng, kSampleCount);
  const double n = kSampleCount;
  for (const double x : samples) ASSERT_GE(x, scale);

  const double expected_mean = shape * scale / (shape - 1.0);
  const double stddev = scale * std::sqrt(shape / ((shape - 1.0) * (shape - 1.0) * (shape - 2.0)));
  EXPECT_NEAR(sample_moments(samples).mean, expected_mean, 6.0 * stddev / std::sqrt(n));
  EXPECT_NEAR(model->mean_s(), expected_mean, 1e-15);

  for (const double x : {2.0 * scale, 4.0 * scale}) {
    const double expected_tail = std::pow(scale / x, shape);
    int above = 0;
    for (const double sample : samples) above += sample > x ? 1 : 0;
    EXPECT_NEAR(above / n, expected_tail, 5.0 * std::sqrt(expected_tail * (1.0 - expected_tail) / n))
        << "P(X > " << x << ")";
  }
}

TEST(ParetoDelay, CappedSamplesNeverExceedMaxAndMeanMatchesIntegral) {
  const double scale = 0.001;
  const double shape = 1.5;
  const double cap = 0.01;
  auto model = make_pareto_delay(scale, shape, cap);
  RandomStream rng(32);
  const auto samples = draw_delays(*model, rng, kSampleCount);
  int at_cap = 0;
  for (const double x : samples) {
    ASSERT_LE(x, cap);
    at_cap += x == cap ? 1 : 0;
  }
  const double n = kSampleCount;
  const double p_cap = std::pow(scale / cap, shape);
  EXPECT_NEAR(at_cap / n, p_cap, 5.0 * std::sqrt(p_cap * (1.0 - p_cap) / n));

  // E[min(X, cap)] = x_m + integral of the survival function from x_m to cap (midpoint rule).
  const int steps = 200000;
  const double dx = (cap - scale) / steps;
  double integral = 0.0;
  for (int i = 0; i < steps; ++i) integral += std::pow(scale / (scale + (i + 0.5) * dx), shape) * dx;
  const double expected_mean = scale + integral;
  EXPECT_NEAR(model->mean_s(), expected_mean, 1e-9);
  // Capped variable: stddev <= cap / 2, a safe bound for the standard error.
  EXPECT_NEAR(sample_moments(samples).mean, expected_mean, 5.0 * (cap / 2.0) / std::sqrt(n));
}

TEST(ParetoDelay, InfiniteMeanWhenShapeAtMostOneAndUncapped) {
  EXPECT_TRUE(std::isinf(make_pareto_delay(0.001, 1.0, kInf)->mean_s()));
  EXPECT_TRUE(std::isinf(make_pareto_delay(0.001, 0.5, kInf)->mean_s()));
  EXPECT_NEAR(make_pareto_delay(0.001, 1.0, 0.01)->mean_s(), 0.001 * (1.0 + std::log(10.0)), 1e-15);
}

TEST(ParetoDelay, RejectsBadParameters) {
  expect_invalid_argument([] { make_pareto_delay(0.0, 2.0, kInf); }, {"pareto delay", "scale", "> 0"});
  expect_invalid_argument([] { make_pareto_delay(-0.001, 2.0, kInf); }, {"pareto delay", "scale"});
  expect_invalid_argument([] { make_pareto_delay(0.001, 0.0, kInf); }, {"pareto delay", "shape", "> 0"});
  expect_invalid_argument([] { make_pareto_delay(0.001, kNaN, kInf); }, {"pareto delay", "shape", "nan"});
  expect_invalid_argument([] { make_pareto_delay(0.001, 2.0, 0.0005); },
                          {"pareto delay", "max", ">= scale", "max=0.0005 s"});
  expect_invalid_argument([] { make_pareto_delay(0.001, 2.0, kNaN); }, {"pareto delay", "max", "nan"});
}

TEST(ParetoDelay, DescribeShowsParameters) {
  EXPECT_EQ(make_pareto_delay(0.001, 2.5, 0.02)->describe(), "pareto(scale 1 ms, shape 2.5, max 20 ms)");
  EXPECT_EQ(make_pareto_delay(0.001, 2.5, kInf)->describe(), "pareto(scale 1 ms, shape 2.5)");
}

}  // namespace
}  // namespace netmc::netsim
