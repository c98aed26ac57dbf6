#include "netsim/freshness_filter.hpp"

#include <gtest/gtest.h>

namespace netmc::netsim {
namespace {

TEST(FreshnessFilter, AcceptsOnlyNewerSequences) {
  FreshnessFilter filter;
  EXPECT_FALSE(filter.last_accepted().has_value());
  EXPECT_TRUE(filter.accept(0));  // the very first message, even sequence 0, is fresh
  EXPECT_TRUE(filter.accept(2));
  EXPECT_FALSE(filter.accept(1));  // older: stale
  EXPECT_FALSE(filter.accept(2));  // duplicate
  EXPECT_TRUE(filter.accept(5));   // gaps are fine
  EXPECT_EQ(filter.stale_dropped(), 2u);
  EXPECT_EQ(filter.last_accepted(), 5u);
}

TEST(FreshnessFilter, ResetForgetsHistory) {
  FreshnessFilter filter;
  filter.accept(10);
  filter.accept(3);
  filter.reset();
  EXPECT_EQ(filter.stale_dropped(), 0u);
  EXPECT_FALSE(filter.last_accepted().has_value());
  EXPECT_TRUE(filter.accept(3));
}

}  // namespace
}  // namespace netmc::netsim
