// The axis node's checks of a job's samples against its reference: the following-error limit,
// frozen and jumping feedback, each against a closed form of when it must trip; none at
// standstill, below the frozen check's reference speed, or in a normal job of netmc's simulated
// drive; the default following-error limit's formula.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "server/drive/axis_limits.hpp"
#include "server/drive/feedback_supervision.hpp"
#include "server/drive/simulated_drive.hpp"
#include "server/drive/supervised_axis.hpp"
#include "tests/drive/linear_servo_plant.hpp"
#include "tests/drive/power_state_printer.hpp"

namespace netmc::drive {
namespace {

constexpr double kNone = std::numeric_limits<double>::infinity();
constexpr double kH = 0.005;

SupervisedSample at(std::uint64_t k, double reference_m, double position_m, double velocity_m_s = 0.0) {
  const double t = static_cast<double>(k) * kH;
  return SupervisedSample{k, t, t, reference_m, position_m, velocity_m_s, t};
}

// Where a reference at `speed_m_s` from 0 is at cycle k.
double ramp(double speed_m_s, std::uint64_t k) { return speed_m_s * kH * static_cast<double>(k); }

// The first cycle that trips, or nullopt; the trip's text in `why`.
template <class SampleOf>
std::optional<std::uint64_t> first_trip(FeedbackSupervision& checks, std::uint64_t cycles, SampleOf sample_of,
                                        std::string* why = nullptr) {
  checks.begin();
  for (std::uint64_t k = 0; k < cycles; ++k) {
    if (const auto reason = checks.check(sample_of(k))) {
      if (why) *why = *reason;
      return k;
    }
  }
  return std::nullopt;
}

TEST(FeedbackSupervision, FollowingErrorTripsAtTheFirstSampleBeyondTheLimitNotBefore) {
  // The reference ramps at 90 mm/s from an axis that stays at 0: the error is 0.45 k mm, 1.8 mm
  // at k = 4 and 2.25 mm at k = 5, the first beyond 2 mm.
  FeedbackSupervision checks(2e-3, kNone, false);
  std::string why;
  const auto trip = first_trip(checks, 100, [](std::uint64_t k) { return at(k, ramp(0.09, k), 0.0); }, &why);
  ASSERT_TRUE(trip);
  EXPECT_EQ(*trip, 5u);
  EXPECT_NE(why.find("following error 2.25 mm beyond the 2 mm limit at cycle 5"), std::string::npos) << why;
  // Either sign: the axis ahead of its reference.
  EXPECT_EQ(first_trip(checks, 100, [](std::uint64_t k) { return at(k, 0.0, ramp(0.09, k)); }), 5u);
}

TEST(FeedbackSupervision, AFrozenEncoderTripsAtItsThirdIdenticalSample) {
  // The axis follows a 90 mm/s ramp exactly until its encoder freezes at cycle 10: samples 10,
  // 11 and 12 read 0.05012 m at 0.09 m/s, and the third trips, the reference 0.9 mm further
  // (2 periods at 90 mm/s).
  FeedbackSupervision checks(kNone, kNone);
  const auto reference = [](std::uint64_t k) { return 0.05012 + 0.09 * kH * (static_cast<double>(k) - 10.0); };
  std::string why;
  const auto trip = first_trip(
      checks, 100,
      [&](std::uint64_t k) { return at(k, reference(k), k < 10 ? reference(k) : reference(10), 0.09); }, &why);
  ASSERT_TRUE(trip);
  EXPECT_EQ(*trip, 12u);
  EXPECT_NE(why.find("feedback frozen: position 0.05012 m unchanged for 3 samples while the reference moved 0.9 mm"),
            std::string::npos)
      << why;
}

TEST(FeedbackSupervision, NoFrozenTripAtStandstillOrBelowTheReferenceSpeed) {
  FeedbackSupervision checks(2e-3, 0.5);
  // At rest for 10 s with the reference at rest.
  EXPECT_FALSE(first_trip(checks, 2000, [](std::uint64_t k) { return at(k, 0.05, 0.05); }));
  // A reference creeping at 19 mm/s (below 20 mm/s) past an axis that reads the same for 50
  // samples (a coarse encoder on a slow axis): no frozen trip; 21 mm/s trips at the third.
  FeedbackSupervision frozen_only(kNone, kNone);
  EXPECT_FALSE(first_trip(frozen_only, 50, [](std::uint64_t k) { return at(k, 0.05 + ramp(0.019, k), 0.05); }));
  EXPECT_EQ(first_trip(frozen_only, 50, [](std::uint64_t k) { return at(k, 0.05 + ramp(0.021, k), 0.05); }), 2u);
  // Samples 1-3 read in a burst 0.1 ms apart (a node catching up after a stall) repeat a moving
  // axis's coarse count: no trip on them; an encoder that stays frozen trips once three of its
  // readings were latched at least a period apart (samples 3, 4 and 5: 9.7 ms).
  const auto burst = [](std::uint64_t k) {
    SupervisedSample sample = at(k, 0.05 + ramp(0.09, k), k == 0 ? 0.0499 : 0.05);
    if (k >= 1 && k <= 3) sample.read_start_s = sample.time_s = 3 * kH + 1e-4 * static_cast<double>(k);
    return sample;
  };
  EXPECT_EQ(first_trip(frozen_only, 50, burst), 5u);
  // Repeated position with a changing velocity is no frozen encoder.
  EXPECT_FALSE(first_trip(frozen_only, 50, [](std::uint64_t k) {
    return at(k, 0.05 + ramp(0.09, k), 0.05, 1e-6 * static_cast<double>(k % 2));
  }));
}

TEST(FeedbackSupervision, AJumpBeyondTheVelocityLimitsStepWithItsMarginTripsAtOnce) {
  // Velocity limit 0.5 m/s, h = 5 ms, margin 50 %: a step of 0.5 x 0.005 x 1.5 = 3.75 mm between
  // two samples is the most the axis may move.
  const double allowed = 0.5 * kH * (1.0 + FeedbackSupervision::kJumpMargin);
  FeedbackSupervision checks(kNone, 0.5);
  const auto step_at_7 = [](double step) {
    return [step](std::uint64_t k) {
      const double x = 0.05 + (k >= 7 ? step : 0.0) + 1e-6 * static_cast<double>(k);  // never frozen
      return at(k, x, x, 1e-3 * static_cast<double>(k));
    };
  };
  std::string why;
  EXPECT_EQ(first_trip(checks, 20, step_at_7(allowed + 1e-6), &why), 7u);
  EXPECT_NE(why.find("feedback jumped 3.75 mm within 5 ms at cycle 7, more than the 3.75 mm the velocity limit 0.5 m/s "
                     "allows (with a 50 % margin)"),
            std::string::npos)
      << why;
  EXPECT_FALSE(first_trip(checks, 20, step_at_7(allowed - 2e-6)));  // 1e-6 m of the ramp itself

  // A node that stalls 36 ms between asking for sample 6 and getting its answer, then takes
  // sample 7 at once: the drive may have latched the two readings 36.2 ms apart, over which
  // 0.287 mm at 8 mm/s is no jump; the same step between two quick reads 0.165 ms apart is one.
  const auto stalled = [](double stall_s) {
    return [stall_s](std::uint64_t k) {
      SupervisedSample sample = at(k, 0.05, 0.05 + (k >= 7 ? 0.287e-3 : 0.0), 0.008 + 1e-6 * static_cast<double>(k));
      if (k == 6) sample.time_s += stall_s;
      if (k == 7) sample.read_start_s = sample.time_s = 6 * kH + stall_s + 0.165e-3;
      return sample;
    };
  };
  EXPECT_FALSE(first_trip(checks, 8, stalled(0.036)));
  EXPECT_EQ(first_trip(checks, 8, [](std::uint64_t k) {
    SupervisedSample sample = at(k, 0.05, 0.05 + (k >= 7 ? 0.287e-3 : 0.0), 1e-6 * static_cast<double>(k));
    if (k == 7) sample.read_start_s = sample.time_s = 6 * kH + 0.165e-3;
    return sample;
  }), 7u);
}

TEST(AxisLimits, TheDefaultFollowingErrorLimitIsATenthOfTheWindowBoundedByTheVelocity) {
  AxisLimits limits;
  EXPECT_TRUE(std::isinf(default_following_error_m(limits)));  // no window, no velocity limit
  limits.position_min_m = 0.0;
  limits.position_max_m = 0.12;
  EXPECT_TRUE(std::isinf(default_following_error_m(limits)));  // a window alone: none
  limits.velocity_m_s = 0.5;
  EXPECT_DOUBLE_EQ(default_following_error_m(limits), 0.012);  // 0.12 / 10 < 0.5 x 0.1
  limits.velocity_m_s = 0.05;
  EXPECT_DOUBLE_EQ(default_following_error_m(limits), 0.005);  // 0.05 x 0.1 < 0.012
  limits.velocity_m_s = 0.5;
  limits.position_max_m = 0.005;
  EXPECT_DOUBLE_EQ(default_following_error_m(limits), 0.001);  // at least 1 mm
  limits.following_error_m = 0.002;
  EXPECT_DOUBLE_EQ(limits.with_default_following_error().following_error_m, 0.002);  // the operator's stays
  limits.following_error_m = kNone;
  EXPECT_DOUBLE_EQ(limits.with_default_following_error().following_error_m, 0.001);
  limits.following_error_m = -1.0;
  EXPECT_THROW(limits.validate(), std::invalid_argument);
}

// A job-like loop on netmc's simulated drive: a 20 mm circle's x (r = 10 mm in 8 s, paper
// 001's reference) followed by u = x_ref' + 20 (x_ref - x) on the speed-mode servo.
struct CircleRun {
  double max_error_m = 0.0;
  std::optional<std::string> fault;
  PowerState state = PowerState::operation_enabled;
  std::uint64_t samples = 0;
};

CircleRun run_circle(AxisLimits limits, FeedbackSupervision* also = nullptr) {
  constexpr double kR = 0.01, kOmega = 2.0 * M_PI / 8.0, kCx = 0.05;
  const auto reference = [](double t) { return kCx + kR * std::cos(kOmega * t); };
  auto drive = std::make_shared<SimulatedDrive>(linear_servo_plant(), "sim:test");
  drive->open();
  SupervisedAxis axis(drive, 1e9, limits);
  axis.follow_reference(reference, kH);
  axis.begin_iteration(reference(0.0));
  if (also) also->begin();
  CircleRun run;
  for (std::uint64_t k = 1; k <= 1600 && !axis.fault(); ++k) {
    const double t = static_cast<double>(k) * kH;
    const double before = t - kH;
    const double u = -kR * kOmega * std::sin(kOmega * before) + 20.0 * (reference(before) - axis.reading().position_m);
    axis.advance_to(t, {{before, before + 0.0005, k, u}});
    run.max_error_m = std::max(run.max_error_m, std::abs(reference(t) - axis.reading().position_m));
    if (also) {
      const auto reason = also->check(at(k, reference(t), axis.reading().position_m, axis.reading().velocity_m_s));
      if (reason && !run.fault) run.fault = *reason;
    }
    ++run.samples;
  }
  if (axis.fault()) run.fault = *axis.fault();
  run.state = axis.power_state();
  return run;
}

TEST(FeedbackSupervision, ANormalSimulatedJobNeverComesNearATrip) {
  // Limits as a node gives them: window [0, 0.12] m, 0.5 m/s, the default 12 mm following error;
  // the frozen check watched beside (the simulated drive's own axis leaves it out).
  AxisLimits limits;
  limits.position_min_m = 0.0;
  limits.position_max_m = 0.12;
  limits.velocity_m_s = 0.5;
  limits = limits.with_default_following_error();
  FeedbackSupervision frozen_too(limits.following_error_m, limits.velocity_m_s, true);
  const CircleRun run = run_circle(limits, &frozen_too);
  EXPECT_FALSE(run.fault) << *run.fault;
  EXPECT_EQ(run.samples, 1600u);
  EXPECT_LT(run.max_error_m, 0.1e-3);  // a hundredth of the 12 mm limit (and below 1 mm, the floor)
}

TEST(SupervisedAxis, AFollowingErrorBeyondTheLimitTripsNamingItAndQuickStops) {
  // The same loop under a 1 um limit, which its errors of some micrometres cross: a trip, with
  // the axis quick-stopping (Fault reaction active until it stands still).
  AxisLimits limits;
  limits.following_error_m = 1e-6;
  const CircleRun run = run_circle(limits);
  ASSERT_TRUE(run.fault);
  EXPECT_NE(run.fault->find("following error"), std::string::npos) << *run.fault;
  EXPECT_NE(run.fault->find("beyond the 0.001 mm limit at cycle"), std::string::npos) << *run.fault;
  EXPECT_EQ(run.state, PowerState::fault_reaction_active);
  EXPECT_LT(run.samples, 1600u);
}

}  // namespace
}  // namespace netmc::drive
