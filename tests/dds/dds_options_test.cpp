// The edge of the DDS layer that needs no peer: interface choice, the clocks of --time-base, and
// the check of a sample's claimed origin.
#include <gtest/gtest.h>

#include <time.h>

#include <cmath>

#include "server/dds/dds_context.hpp"
#include "server/dds/dds_locators.hpp"
#include "server/dds/time_base.hpp"

namespace netmc::dds {
namespace {

TEST(Interfaces, DefaultIsLoopbackAndNamesResolveToTheirAddress) {
  EXPECT_EQ(resolve_interfaces({}), (std::vector<std::string>{"127.0.0.1"}));
  EXPECT_EQ(resolve_interfaces({"lo"}), (std::vector<std::string>{"127.0.0.1"}));
  EXPECT_EQ(resolve_interfaces({"10.1.2.3", "127.0.0.1"}), (std::vector<std::string>{"10.1.2.3", "127.0.0.1"}));
  EXPECT_EQ(resolve_interfaces({"any"}), (std::vector<std::string>{"any"}));
}

TEST(Interfaces, UnknownNamesAndMalformedAddressesNameTheFlag) {
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"no-such-if0"}, {"300.1.1.1"}, {"any", "lo"}, {std::string(80, 'e')}}) {
    try {
      resolve_interfaces(bad);
      ADD_FAILURE() << bad[0] << " was accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_EQ(std::string(error.what()).rfind("--interface: ", 0), 0u) << error.what();
    }
  }
}

TEST(SentBy, TheClaimedIdentityMustBeTheSendersPrefixDigitForDigit) {
  eprosima::fastrtps::rtps::GuidPrefix_t sender;
  for (std::size_t i = 0; i < sender.size; ++i) sender.value[i] = static_cast<eprosima::fastrtps::rtps::octet>(0x0f + 17 * i);
  const std::string identity = prefix_text(sender);  // the second method: snprintf("%02x")
  ASSERT_EQ(identity, "0f2031425364758697a8b9ca");
  EXPECT_TRUE(sent_by(sender, identity));
  // Any one digit off, upper case, too short, too long, empty: another participant.
  for (std::size_t i = 0; i < identity.size(); ++i) {
    std::string other = identity;
    other[i] = other[i] == '0' ? '1' : '0';
    EXPECT_FALSE(sent_by(sender, other)) << other;
  }
  for (const std::string& other : {std::string("0F2031425364758697A8B9CA"), identity.substr(1), identity + "0",
                                  std::string()}) {
    EXPECT_FALSE(sent_by(sender, other)) << other;
  }
}

TEST(TimeBase, APastSystemInstantMapsToEveryBase) {
  // A reception timestamp 250 ms old, read on each base: that base's now minus 250 ms.
  const auto past = std::chrono::system_clock::now() - std::chrono::milliseconds(250);
  for (const TimeBase base : {TimeBase::monotonic, TimeBase::realtime, TimeBase::tai}) {
    EXPECT_NEAR(time_base_at_s(base, past), time_base_now_s(base) - 0.25, 0.01);
  }
}

TEST(TimeBase, ReadsTheKernelClocks) {
  const auto reading = [](clockid_t id) {
    timespec t{};
    ::clock_gettime(id, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
  };
  EXPECT_NEAR(time_base_now_s(TimeBase::monotonic), reading(CLOCK_MONOTONIC), 0.05);
  EXPECT_NEAR(time_base_now_s(TimeBase::realtime), reading(CLOCK_REALTIME), 0.05);
  EXPECT_NEAR(time_base_now_s(TimeBase::tai), reading(CLOCK_TAI), 0.05);
  EXPECT_EQ(parse_time_base("tai"), TimeBase::tai);
  EXPECT_THROW(parse_time_base("gps"), std::invalid_argument);
}

TEST(TimeBase, AnInstantOnAnyClockMapsToTheSameSteadyInstant) {
  // 2 s from now, read on each clock, is one steady-clock instant (to scheduling noise).
  const auto expected = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  for (const TimeBase base : {TimeBase::monotonic, TimeBase::realtime, TimeBase::tai}) {
    const auto mapped = steady_time_at(base, time_base_now_s(base) + 2.0);
    EXPECT_LT(std::abs(std::chrono::duration<double>(mapped - expected).count()), 0.05) << time_base_name(base);
  }
}

}  // namespace
}  // namespace netmc::dds
