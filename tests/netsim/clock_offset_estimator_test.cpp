#include "netsim/clock_offset_estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace netmc::netsim {
namespace {

// An exchange over a path with the given one-way delays, against a remote clock that reads
// local + offset.
TimeTransferExchange exchange(double t1, double offset, double out_delay, double turnaround,
                              double back_delay) {
  const double t2 = t1 + out_delay + offset;
  const double t3 = t2 + turnaround;
  const double t4 = t3 - offset + back_delay;
  return {t1, t2, t3, t4};
}

TEST(ClockOffsetEstimator, SymmetricPathGivesTheExactOffsetAndRoundTrip) {
  ClockOffsetEstimator estimator;
  ASSERT_TRUE(estimator.add(exchange(100.0, 86400.0, 0.0004, 0.0001, 0.0004)));
  const auto e = estimator.estimate();
  ASSERT_TRUE(e);
  EXPECT_NEAR(e->offset_s, 86400.0, 1e-9);
  EXPECT_NEAR(e->round_trip_s, 0.0008, 1e-9);
  EXPECT_NEAR(e->uncertainty_s, 0.0004, 1e-9);
}

TEST(ClockOffsetEstimator, AsymmetryErrsByHalfTheDifferenceWithinTheStatedUncertainty) {
  ClockOffsetEstimator estimator;
  // 3 ms out, 1 ms back: the estimate is off by (3 - 1) / 2 = 1 ms, inside +- rtt/2 = 2 ms.
  estimator.add(exchange(5.0, -3600.0, 0.003, 0.0, 0.001));
  const auto e = estimator.estimate();
  ASSERT_TRUE(e);
  EXPECT_NEAR(e->offset_s - (-3600.0), 0.001, 1e-9);
  EXPECT_LE(std::abs(e->offset_s + 3600.0), e->uncertainty_s);
}

TEST(ClockOffsetEstimator, UsesTheExchangeWithTheShortestRoundTrip) {
  ClockOffsetEstimator estimator(8);
  estimator.add(exchange(1.0, 42.0, 0.010, 0.0, 0.001));   // queued on the way out
  estimator.add(exchange(2.0, 42.0, 0.0002, 0.0, 0.0002)); // clean
  estimator.add(exchange(3.0, 42.0, 0.001, 0.0, 0.020));   // queued on the way back
  const auto e = estimator.estimate();
  ASSERT_TRUE(e);
  EXPECT_NEAR(e->offset_s, 42.0, 1e-9);
  EXPECT_NEAR(e->round_trip_s, 0.0004, 1e-9);
  EXPECT_EQ(e->exchanges, 3u);
}

TEST(ClockOffsetEstimator, TheWindowForgetsOldExchanges) {
  ClockOffsetEstimator estimator(2);
  estimator.add(exchange(1.0, 7.0, 0.0001, 0.0, 0.0001));  // best, but it ages out
  estimator.add(exchange(2.0, 9.0, 0.002, 0.0, 0.002));
  estimator.add(exchange(3.0, 9.0, 0.003, 0.0, 0.003));
  const auto e = estimator.estimate();
  ASSERT_TRUE(e);
  EXPECT_NEAR(e->offset_s, 9.0, 1e-9);
  EXPECT_EQ(e->exchanges, 2u);
}

TEST(ClockOffsetEstimator, RejectsNonCausalAndNonFiniteExchanges) {
  ClockOffsetEstimator estimator;
  EXPECT_FALSE(estimator.estimate());
  EXPECT_FALSE(estimator.add({2.0, 5.0, 5.1, 1.0}));                  // back before it left
  EXPECT_FALSE(estimator.add({1.0, 5.0, 4.0, 2.0}));                  // replied before received
  EXPECT_FALSE(estimator.add({1.0, 5.0, 7.0, 2.0}));                  // turnaround longer than the trip
  EXPECT_FALSE(estimator.add({1.0, std::nan(""), 5.0, 2.0}));
  EXPECT_FALSE(estimator.add({1.0, 5.0, INFINITY, 2.0}));
  EXPECT_FALSE(estimator.estimate());
}

}  // namespace
}  // namespace netmc::netsim
