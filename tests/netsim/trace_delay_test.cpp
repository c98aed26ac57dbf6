#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "netsim/delay_model.hpp"
#include "netsim_test_support.hpp"

namespace netmc::netsim {
namespace {

using test::draw_delays;
using test::expect_invalid_argument;

TEST(TraceDelay, ReplaysInOrderAndWraps) {
  auto model = make_trace_delay({0.003, 0.001, 0.002});
  RandomStream rng(1);
  EXPECT_EQ(draw_delays(*model, rng, 7), (std::vector<double>{0.003, 0.001, 0.002, 0.003, 0.001, 0.002, 0.003}));
  EXPECT_DOUBLE_EQ(model->mean_s(), 0.002);
  EXPECT_EQ(model->describe(), "trace(3 samples, mean 2 ms)");
}

TEST(TraceDelay, ResetAndCloneStartFromTheFirstSample) {
  auto model = make_trace_delay({0.003, 0.001});
  RandomStream rng(1);
  model->next_delay_s(rng);
  auto clone = model->clone();
  EXPECT_EQ(clone->next_delay_s(rng), 0.003);
  EXPECT_EQ(model->next_delay_s(rng), 0.001);  // the clone did not move the original
  model->reset();
  EXPECT_EQ(model->next_delay_s(rng), 0.003);
}

TEST(TraceDelay, DoesNotConsumeRandomNumbers) {
  auto model = make_trace_delay({0.001});
  RandomStream used(5);
  RandomStream untouched(5);
  model->next_delay_s(used);
  EXPECT_EQ(used.next_u64(), untouched.next_u64());
}

TEST(TraceDelay, RejectsEmptyNegativeAndNaN) {
  expect_invalid_argument([] { make_trace_delay({}); }, {"trace delay", "delays_s", "empty"});
  expect_invalid_argument([] { make_trace_delay({0.001, -0.002}); }, {"trace delay", "delays_s[1]", "in [0, 60] s", "-0.002"});
  expect_invalid_argument([] { make_trace_delay({std::numeric_limits<double>::quiet_NaN()}); },
                          {"trace delay", "delays_s[0]", "nan"});
}

}  // namespace
}  // namespace netmc::netsim
