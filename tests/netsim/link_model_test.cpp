#include "netsim/link_model.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "netsim_test_support.hpp"

namespace netmc::netsim {
namespace {

using test::expect_invalid_argument;

LinkModel make_lossy_link(double loss_probability, std::uint64_t seed) {
  return LinkModel(make_uniform_delay(0.001, 0.005), make_bernoulli_loss(loss_probability), RandomStream(seed));
}

std::vector<LinkModel::Transit> transmit_many(LinkModel& link, int count) {
  std::vector<LinkModel::Transit> transits;
  for (int i = 0; i < count; ++i) transits.push_back(link.transmit());
  return transits;
}

void expect_same(const std::vector<LinkModel::Transit>& a, const std::vector<LinkModel::Transit>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].lost, b[i].lost) << "packet " << i;
    EXPECT_EQ(a[i].delay_s, b[i].delay_s) << "packet " << i;
  }
}

TEST(LinkModel, SameSeedGivesIdenticalTransits) {
  LinkModel a = make_lossy_link(0.3, 61);
  LinkModel b = make_lossy_link(0.3, 61);
  expect_same(transmit_many(a, 500), transmit_many(b, 500));
}

TEST(LinkModel, DelayDrawsDoNotDependOnLoss) {
  // Both links draw one loss number per packet, so their delay draws line up packet by packet.
  LinkModel lossy = make_lossy_link(0.3, 62);
  LinkModel lossless = make_lossy_link(0.0, 62);
  const auto with_loss = transmit_many(lossy, 1000);
  const auto without_loss = transmit_many(lossless, 1000);
  int lost = 0;
  for (std::size_t i = 0; i < with_loss.size(); ++i) {
    lost += with_loss[i].lost ? 1 : 0;
    EXPECT_FALSE(without_loss[i].lost);
    EXPECT_EQ(with_loss[i].delay_s, without_loss[i].delay_s) << "packet " << i;
  }
  EXPECT_GT(lost, 200);
  EXPECT_LT(lost, 400);
}

TEST(LinkModel, CopyAndMoveKeepParametersAndStream) {
  LinkModel original = make_lossy_link(0.2, 63);
  LinkModel copy(original);
  LinkModel assigned = make_lossy_link(0.9, 1);
  assigned = original;
  const auto expected = transmit_many(original, 200);
  expect_same(transmit_many(copy, 200), expected);
  expect_same(transmit_many(assigned, 200), expected);

  LinkModel source = make_lossy_link(0.2, 63);
  LinkModel moved(std::move(source));
  expect_same(transmit_many(moved, 200), expected);
  LinkModel move_assigned = make_lossy_link(0.9, 1);
  move_assigned = std::move(moved);
  move_assigned.reset(RandomStream(63));
  expect_same(transmit_many(move_assigned, 200), expected);
}

TEST(LinkModel, ResetRestoresModelsAndStream) {
  LinkModel link(make_trace_delay({0.003, 0.001, 0.002}), make_gilbert_elliott_loss(0.3, 0.3, 0.0, 1.0),
                 RandomStream(64));
  const auto first = transmit_many(link, 50);
  link.reset(RandomStream(64));
  expect_same(transmit_many(link, 50), first);
  EXPECT_EQ(first[0].delay_s, 0.003);
  EXPECT_EQ(first[1].delay_s, 0.001);
}

TEST(LinkModel, DescribeAndAccessors) {
  LinkModel link(make_constant_delay(0.002), make_bernoulli_loss(0.01), RandomStream(1));
  EXPECT_EQ(link.describe(), "delay constant(2 ms), loss bernoulli(p 0.01)");
  EXPECT_EQ(link.delay_model().mean_s(), 0.002);
  EXPECT_EQ(link.loss_model().mean_loss_rate(), 0.01);
}

TEST(LinkModel, RejectsNullModels) {
  expect_invalid_argument([] { LinkModel(nullptr, make_no_loss(), RandomStream(1)); }, {"link model", "delay"});
  expect_invalid_argument([] { LinkModel(make_no_delay(), nullptr, RandomStream(1)); }, {"link model", "loss"});
}

}  // namespace
}  // namespace netmc::netsim
