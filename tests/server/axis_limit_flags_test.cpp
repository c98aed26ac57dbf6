// netmc-axis's limit flags: one value for every axis, or AXIS=VALUE entries that override it.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "server/axis/axis_limit_flags.hpp"

namespace netmc::axis {
namespace {

const std::vector<std::string> kAxes{"stage1.x", "stage1.y", "z-2"};

std::string error_of(const AxisLimitFlags& flags) {
  try {
    parse_axis_limits(flags, kAxes);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(accepted)";
}

TEST(AxisLimitFlags, NoFlagLeavesEveryAxisUnlimited) {
  const auto limits = parse_axis_limits({}, kAxes);
  ASSERT_EQ(limits.size(), 3u);
  for (const auto& axis : kAxes) EXPECT_FALSE(limits.at(axis).any()) << axis;
  EXPECT_EQ(describe_axis_limits(limits, kAxes), "stage1.x: none; stage1.y: none; z-2: none");
}

TEST(AxisLimitFlags, AValueAppliesToEveryAxisAndAnAxisEntryOverridesIt) {
  AxisLimitFlags flags;
  flags.command = "8,stage1.y=5";
  flags.position_window = "-0.05:0.25,z-2=-1e-3:2.5e-2";
  flags.velocity = "stage1.x=1.5";
  flags.slew = "stage1.y=100,1000";  // later entries win: every axis 1000
  const auto limits = parse_axis_limits(flags, kAxes);
  EXPECT_EQ(limits.at("stage1.x").command, 8.0);
  EXPECT_EQ(limits.at("stage1.y").command, 5.0);
  EXPECT_EQ(limits.at("z-2").command, 8.0);
  EXPECT_EQ(limits.at("stage1.x").position_min_m, -0.05);
  EXPECT_EQ(limits.at("stage1.y").position_max_m, 0.25);
  EXPECT_EQ(limits.at("z-2").position_min_m, -1e-3);
  EXPECT_EQ(limits.at("z-2").position_max_m, 2.5e-2);
  EXPECT_EQ(limits.at("stage1.x").velocity_m_s, 1.5);
  EXPECT_TRUE(std::isinf(limits.at("stage1.y").velocity_m_s));
  for (const auto& axis : kAxes) EXPECT_EQ(limits.at(axis).slew_per_s, 1000.0) << axis;
  EXPECT_EQ(describe_axis_limits(limits, {"stage1.y"}),
            "stage1.y: command 5, position [-0.05, 0.25] m, slew 1000/s");
}

TEST(AxisLimitFlags, BadEntriesNameTheFlagTheAxisAndTheForm) {
  AxisLimitFlags flags;
  flags.command = "8,stage9.x=5";
  EXPECT_EQ(error_of(flags), "--command-limit: 'stage9.x' is not an axis of this node (--axes)");
  flags = {};
  flags.position_window = "stage1.y=0.3:0.1";
  EXPECT_EQ(error_of(flags),
            "--position-window (axis stage1.y): expected MIN:MAX (m, MIN < MAX) or AXIS=MIN:MAX (m, MIN < MAX) "
            "entries separated by commas, got 'stage1.y=0.3:0.1'");
  // Each of these is refused with the flag's name and its expected form, never taken as a limit.
  for (const std::string bad : {"", "0", "-1", "nan", "inf", "1e400", "5V", "stage1.x=", "=5", "5,,6", "0x10"}) {
    flags = {};
    flags.velocity = bad.empty() ? "," : bad;
    EXPECT_NE(error_of(flags).find("--velocity-limit"), std::string::npos) << bad << ": " << error_of(flags);
    EXPECT_NE(error_of(flags).find("expected a positive number V (m/s)"), std::string::npos) << bad;
  }
  for (const std::string bad : {"0.1", "0.1:", ":0.1", "0.1:0.1", "a:b", "-inf:1", "0:1:2"}) {
    flags = {};
    flags.position_window = bad;
    EXPECT_NE(error_of(flags).find("--position-window: expected MIN:MAX"), std::string::npos)
        << bad << ": " << error_of(flags);
  }
}

}  // namespace
}  // namespace netmc::axis

namespace netmc::axis {
namespace {

TEST(AxisLimitFlags, TheFollowingErrorLimitTakesALengthWithItsUnit) {
  AxisLimitFlags flags;
  flags.following_error = "2mm,z-2=0.5mm";
  const auto limits = parse_axis_limits(flags, kAxes);
  EXPECT_DOUBLE_EQ(limits.at("stage1.x").following_error_m, 0.002);
  EXPECT_DOUBLE_EQ(limits.at("z-2").following_error_m, 0.0005);
  EXPECT_EQ(describe_axis_limits(limits, {"stage1.y"}), "stage1.y: following error 2 mm");
  for (const std::string bad : {"stage1.y=0mm", "-2mm", "2 parsecs", "stage1.y="}) {
    flags.following_error = bad;
    EXPECT_NE(error_of(flags).find("--following-error-limit"), std::string::npos) << bad << ": " << error_of(flags);
    EXPECT_NE(error_of(flags).find("a positive length such as 2mm"), std::string::npos) << bad;
  }
}

}  // namespace
}  // namespace netmc::axis
