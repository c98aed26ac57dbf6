// The operator's commissioning of one axis on netmc's simulated drive (CiA 402, CSP): enable
// holds where the axis stands, a move's duration is the trapezoid's closed form and it ends
// within a micrometre of its target, a jog stops at its deadman and at the window's edge,
// refusals name the limit, a drive that does not follow trips, disable and quick stop bring the
// axis to rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "server/axis/commissioning_axis.hpp"
#include "server/drive/simulated_drive.hpp"
#include "tests/drive/linear_servo_plant.hpp"

namespace netmc::axis {
namespace {

using Motion = CommissioningAxis::Motion;
constexpr double kPoll = 0.002;  // the node's poll period while an axis moves

drive::AxisLimits window(double low, double high) {
  drive::AxisLimits limits;
  limits.position_min_m = low;
  limits.position_max_m = high;
  limits.velocity_m_s = 0.05;
  return limits;
}

struct Rig {
  explicit Rig(double at_m, drive::AxisLimits limits = window(0.0, 0.12), drive::EmulatedDriveSettings settings = {})
      : drive(drive::linear_servo_plant(), "sim:test", settings), axis(CommissioningSettings{}, limits) {
    drive.open();
    drive.restart_at(at_m);
    axis.poll(drive, 0.0);  // the node reads the drive before it takes commands
  }
  // Polls every 2 ms until `done` or `for_s` passes; returns the largest |velocity| and
  // |following error| seen.
  std::pair<double, double> run(double for_s, const std::function<bool()>& done = [] { return false; }) {
    double peak_v = 0.0, peak_error = 0.0;
    const double end = t + for_s;
    while (t < end && !done()) {
      t += kPoll;
      drive.cycle(t);
      const auto reading = axis.poll(drive, t);
      peak_v = std::max(peak_v, std::abs(reading.velocity_m_s));
      peak_error = std::max(peak_error, std::abs(axis.following_error_m()));
    }
    return {peak_v, peak_error};
  }
  drive::PowerState state() { return *drive::decode_statusword(drive.read().statusword); }
  double position() { return drive.read().position_m; }

  drive::SimulatedDrive drive;
  CommissioningAxis axis;
  double t = 0.0;
};

void enable(Rig& rig) {
  ASSERT_EQ(rig.axis.enable(rig.t), "");
  rig.run(1.0, [&] { return rig.axis.motion() == Motion::holding; });
  ASSERT_EQ(rig.axis.motion(), Motion::holding) << rig.axis.note();
}

TEST(CommissioningAxis, EnableHoldsWhereTheAxisStands) {
  Rig rig(0.055);
  EXPECT_EQ(rig.state(), drive::PowerState::switch_on_disabled);
  enable(rig);
  EXPECT_EQ(rig.state(), drive::PowerState::operation_enabled);
  rig.run(0.5);
  EXPECT_NEAR(rig.position(), 0.055, 1e-6);
  EXPECT_EQ(rig.axis.motion(), Motion::holding);
}

TEST(CommissioningAxis, MoveTakesTheTrapezoidsTimeAndEndsAtItsTarget) {
  Rig rig(0.055);
  enable(rig);
  // 10 mm at 10 mm/s with 0.5 m/s^2: d/v + v/a = 1 s + 20 ms.
  const double start = rig.t;
  ASSERT_EQ(rig.axis.move(0.065, 0.01, rig.t), "");
  EXPECT_EQ(rig.axis.motion(), Motion::moving);
  const auto [peak_v, peak_error] = rig.run(5.0, [&] { return rig.axis.motion() == Motion::holding; });
  EXPECT_NEAR(rig.t - start, 1.02, 2 * kPoll);
  // The profile cruises at 10 mm/s; the drive's CSP loop (P on position, velocity fed forward)
  // overshoots it by 17 % at the corners: far inside the 50 mm/s limit.
  EXPECT_LE(peak_v, 0.01 * 1.2);
  EXPECT_LT(peak_error, 0.5e-3);
  rig.run(0.5);
  EXPECT_NEAR(rig.position(), 0.065, 1e-6);
  // And back at the node's positioning speed (0.05 m/s).
  ASSERT_EQ(rig.axis.move(0.055, 0.0, rig.t), "");
  rig.run(5.0, [&] { return rig.axis.motion() == Motion::holding; });
  rig.run(0.5);
  EXPECT_NEAR(rig.position(), 0.055, 1e-6);
  EXPECT_EQ(rig.axis.note(), "");
}

TEST(CommissioningAxis, RefusalsNameTheLimitOrTheState) {
  Rig rig(0.055, window(0.0, 0.12));
  EXPECT_EQ(rig.axis.move(0.06, 0.0, rig.t), "the axis is not enabled (netmc enable NODE AXIS first)");
  EXPECT_NE(rig.axis.jog(0.01, rig.t).find("not enabled"), std::string::npos);
  enable(rig);
  EXPECT_EQ(rig.axis.move(0.2, 0.0, rig.t), "the target 0.2 m is outside the axis's window [0, 0.12] m");
  EXPECT_EQ(rig.axis.move(0.06, 0.5, rig.t), "the speed 0.5 m/s is beyond the axis's velocity limit 0.05 m/s");
  EXPECT_EQ(rig.axis.move(NAN, 0.0, rig.t), "the target must be a finite position in m");
  EXPECT_EQ(rig.axis.move(0.06, -1.0, rig.t), "the speed must be a positive number of m/s");
  EXPECT_EQ(rig.axis.jog(-0.2, rig.t), "the jog speed 0.2 m/s is beyond the axis's velocity limit 0.05 m/s");
  EXPECT_EQ(rig.axis.motion(), Motion::holding);  // nothing refused moved it

  drive::AxisLimits unbounded;
  Rig free_axis(0.0, unbounded);
  enable(free_axis);
  EXPECT_EQ(free_axis.axis.jog(0.01, free_axis.t),
            "the axis has no position window to jog within (netmc-axis --position-window)");
}

TEST(CommissioningAxis, AJogStopsWhenItsCommandsStopComing) {
  Rig rig(0.05);
  enable(rig);
  ASSERT_EQ(rig.axis.jog(0.01, rig.t), "");
  // Renewed for 1 s, then left alone: the deadman stops it 0.5 s later, on the ramp.
  for (int k = 0; k < 10; ++k) {
    rig.run(0.1);
    ASSERT_EQ(rig.axis.jog(0.01, rig.t), "");
  }
  rig.run(3.0, [&] { return rig.axis.motion() == Motion::holding; });
  EXPECT_EQ(rig.axis.note(), "jog stopped: no jog command for 0.5 s (the deadman)");
  // 1.5 s at 10 mm/s, less half the ramps' time (20 ms each way at 0.5 m/s^2): 15 mm.
  rig.run(0.5);
  EXPECT_NEAR(rig.position() - 0.05, 0.015, 0.3e-3);
}

TEST(CommissioningAxis, AJogEndsInsideTheWindowsEdge) {
  Rig rig(0.11, window(0.0, 0.12));
  enable(rig);
  ASSERT_EQ(rig.axis.jog(0.02, rig.t), "");
  for (int k = 0; k < 20 && rig.axis.motion() == Motion::jogging; ++k) {
    rig.run(0.1);
    rig.axis.jog(0.02, rig.t);
  }
  rig.run(1.0, [&] { return rig.axis.motion() == Motion::holding; });
  EXPECT_EQ(rig.axis.note(), "jog ended at the window's edge");
  rig.run(0.5);
  EXPECT_LE(rig.position(), 0.12);
  EXPECT_NEAR(rig.position(), 0.12 - 0.12e-3, 1e-6);
  EXPECT_NE(rig.axis.jog(0.02, rig.t).find("upper edge"), std::string::npos);
  EXPECT_EQ(rig.axis.jog(-0.02, rig.t), "");  // away from it is fine
}

TEST(CommissioningAxis, ADriveThatDoesNotFollowTripsIntoAQuickStop) {
  // A power stage too weak to accelerate the axis: the profile runs away from it.
  drive::EmulatedDriveSettings weak;
  weak.max_input = 1e-4;
  Rig rig(0.05, window(0.0, 0.12), weak);
  enable(rig);
  ASSERT_EQ(rig.axis.move(0.1, 0.05, rig.t), "");
  rig.run(2.0, [&] { return !rig.axis.active(); });
  EXPECT_FALSE(rig.axis.active());
  EXPECT_NE(rig.axis.note().find("following error 2.0"), std::string::npos) << rig.axis.note();
  EXPECT_NE(rig.axis.note().find("beyond the limit 2.000 mm"), std::string::npos);
  rig.run(1.0);
  EXPECT_NE(rig.state(), drive::PowerState::operation_enabled);
}

TEST(CommissioningAxis, DisableRampsToRestThenSwitchesOff) {
  Rig rig(0.02);
  enable(rig);
  ASSERT_EQ(rig.axis.move(0.1, 0.05, rig.t), "");
  rig.run(0.5);  // at speed: 50 mm/s
  EXPECT_GT(std::abs(rig.drive.read().velocity_m_s), 0.04);
  rig.axis.disable(rig.drive, rig.t);
  EXPECT_EQ(rig.axis.motion(), Motion::stopping);
  const double at = rig.position();
  rig.run(1.0, [&] { return !rig.axis.active(); });
  EXPECT_FALSE(rig.axis.active());
  EXPECT_EQ(rig.state(), drive::PowerState::ready_to_switch_on);
  // Stopped on the ramp: v^2 / (2 a) = 2.5 mm past where it was asked.
  EXPECT_NEAR(rig.position() - at, 0.0025, 0.3e-3);
}

TEST(CommissioningAxis, QuickStopIsTheDrivesOwn) {
  Rig rig(0.02);
  enable(rig);
  ASSERT_EQ(rig.axis.move(0.1, 0.05, rig.t), "");
  rig.run(0.5);
  rig.axis.quick_stop(rig.drive);
  EXPECT_FALSE(rig.axis.active());
  EXPECT_EQ(rig.axis.note(), "quick stop by the operator");
  EXPECT_EQ(rig.state(), drive::PowerState::quick_stop_active);
  rig.run(1.0);
  EXPECT_EQ(rig.state(), drive::PowerState::switch_on_disabled);
  EXPECT_LT(std::abs(rig.drive.read().velocity_m_s), 1e-3);
}

}  // namespace
}  // namespace netmc::axis
