// SampleIntake on real Fast DDS readers (three participants of one process, UDP on loopback): a
// flood of forged job controls that arrives after a server's BEGIN_ITERATION, before the node's
// loop takes it, pushes the BEGIN out of a plain reader's keep-last history (what the node had),
// not out of the intake, which drops the forgeries on the receive thread as they arrive.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <string>

#include "dds_typesPubSubTypes.h"
#include "server/axis/sample_intake.hpp"
#include "server/dds/dds_context.hpp"
#include "server/dds/topics.hpp"

namespace {

namespace nd = netmc::dds;
using eprosima::fastrtps::rtps::GuidPrefix_t;

// Outside the integration scripts' domains (100-199), so a concurrent script never meets it.
constexpr int kDomain = 212;

nd::DdsOptions loopback(const std::string& name) {
  nd::DdsOptions options;
  options.domain_id = kDomain;
  options.transport = nd::Transport::udp;  // loopback only: no interface named
  options.name = name;
  return options;
}

TEST(SampleIntake, AFloodOfForgedJobControlsCannotPushOutTheServersBegin) {
  nd::DdsContext node(loopback("intake-node"));
  nd::DdsContext server(loopback("intake-server"));
  nd::DdsContext forger(loopback("intake-forger"));
  auto* topic = node.topic<nd::JobControlPubSubType>(nd::kJobControlTopic);
  netmc::axis::SampleIntake<nd::JobControl> intake(
      [](const GuidPrefix_t& sender, const nd::JobControl& control) { return nd::sent_by(sender, control.server()); },
      64);
  node.reader(topic, nd::Delivery::control, {}, &intake);
  nd::SampleReader<nd::JobControl> plain(node.reader(topic, nd::Delivery::control));
  auto* server_writer =
      server.writer(server.topic<nd::JobControlPubSubType>(nd::kJobControlTopic), nd::Delivery::control);
  auto* forger_writer =
      forger.writer(forger.topic<nd::JobControlPubSubType>(nd::kJobControlTopic), nd::Delivery::control);
  ASSERT_TRUE(nd::wait_for_readers(server_writer, 2, std::chrono::seconds(20)));
  ASSERT_TRUE(nd::wait_for_readers(forger_writer, 2, std::chrono::seconds(20)));

  nd::JobControl begin;
  begin.axis("x");
  begin.server(server.identity());
  begin.job_id(7);
  begin.iteration(1);
  begin.kind(nd::CONTROL_BEGIN_ITERATION);
  nd::write_checked(server_writer, &begin);
  ASSERT_EQ(server_writer->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(10, 0)), ReturnCode_t::RETCODE_OK);
  constexpr std::uint64_t kForgeries = 1000;
  for (std::uint64_t i = 0; i < kForgeries; ++i) {
    nd::JobControl forged = begin;  // in the server's name, from the forger's participant
    forged.kind(nd::CONTROL_END_JOB);
    forged.job_id(1000 + i);
    nd::write_checked(forger_writer, &forged);
  }
  ASSERT_EQ(forger_writer->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(10, 0)), ReturnCode_t::RETCODE_OK);

  // The plain reader keeps the newest 64 of axis x: forgeries only.
  std::size_t kept = 0;
  while (const auto control = plain.try_take()) {
    ++kept;
    EXPECT_NE(control->job_id(), 7u) << "the BEGIN survived the flood in the plain reader's history";
  }
  EXPECT_EQ(kept, 64u);
  // The intake kept the BEGIN, and only it.
  const auto taken = intake.take();
  ASSERT_TRUE(taken.has_value());
  EXPECT_EQ(taken->kind(), nd::CONTROL_BEGIN_ITERATION);
  EXPECT_EQ(taken->job_id(), 7u);
  EXPECT_TRUE(nd::sent_by(intake.last_sender(), server.identity()));
  EXPECT_FALSE(intake.take().has_value());
  // A keep-last writer may drop its own unacknowledged samples when it writes faster than they
  // are acknowledged: at least the last 64 arrive.
  EXPECT_GE(intake.dropped(), 64u);
  EXPECT_LE(intake.dropped(), kForgeries);
}

}  // namespace
