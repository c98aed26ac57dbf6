// The virtual-time loop: delay accounting, long delays, reordering, loss, deadlines, determinism.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "server/sim/contour_job_runner.hpp"
#include "sim_test_support.hpp"

namespace netmc::sim {
namespace {

using testing::small_circle_job;

TEST(ContourJobRunner, WithoutNetworkEffectsEveryCommandActsAtItsSample) {
  ContourJob job = small_circle_job();
  job.record_traces = true;
  ContourJobRunner runner(job);
  const auto record = runner.run_iteration();
  const auto& m = record.metrics;
  EXPECT_EQ(record.trace.size(), 401u);  // 2 s at 5 ms, samples 0..400
  EXPECT_EQ(m.tau_mean_s, 0.0);
  EXPECT_EQ(m.tau_max_s, 0.0);
  EXPECT_EQ(m.deadline_misses + m.lost_feedback + m.lost_setpoints + m.stale_setpoints, 0u);
  // Zero initial position error: the exact contour error starts at zero.
  EXPECT_NEAR(record.trace.front().contour_error_m, 0.0, 1e-15);
  EXPECT_GT(m.e_max_m, 0.0);
  EXPECT_LT(m.e_max_m, 1e-3);
  // e_sum and e_rms are consistent with the per-sample trace.
  double sum = 0.0, squares = 0.0;
  for (const auto& row : record.trace) {
    sum += std::abs(row.contour_error_m);
    squares += row.contour_error_m * row.contour_error_m;
  }
  EXPECT_NEAR(m.e_sum_m, sum, 1e-15);
  EXPECT_NEAR(m.e_rms_m, std::sqrt(squares / 401.0), 1e-15);
}

TEST(ContourJobRunner, ConstantDelayLongerThanAPeriodIsAccountedExactly) {
  ContourJob job = small_circle_job();
  job.downlink.delay = netsim::make_constant_delay(0.0075);  // 1.5 periods
  job.uplink.delay = netsim::make_constant_delay(0.001);
  job.deadline_s = 0.002;
  ContourJobRunner runner(job);
  const auto m = runner.run_iteration().metrics;
  EXPECT_NEAR(m.tau_mean_s, 0.0085, 1e-12);
  EXPECT_NEAR(m.tau_max_s, 0.0085, 1e-12);
  EXPECT_NEAR(m.tau_p99_s, 0.0085, 1e-12);
  EXPECT_NEAR(m.tau_sc_mean_s, 0.001, 1e-12);
  EXPECT_NEAR(m.tau_ca_mean_s, 0.0075, 1e-12);
  EXPECT_EQ(m.stale_setpoints, 0u);
  EXPECT_EQ(m.deadline_misses, 0u);
}

TEST(ContourJobRunner, FeedbackLaterThanItsDeadlineIsCountedLate) {
  // Uplink 1.5 periods, deadline one period: every cycle k misses its feedback, which arrives
  // within cycle k + 1's deadline; the feedback of cycles 0..N-2 of both axes comes late.
  ContourJob job = small_circle_job();
  job.uplink.delay = netsim::make_constant_delay(0.0075);
  ContourJobRunner runner(job);
  const auto m = runner.run_iteration().metrics;
  const std::uint64_t cycles = job.cycles();
  EXPECT_EQ(m.deadline_misses, cycles);
  EXPECT_EQ(m.late_feedback, 2 * (cycles - 1));
  EXPECT_EQ(m.lost_feedback, 0u);
}

TEST(ContourJobRunner, ReorderedSetpointsAreDroppedAsStale) {
  // Delays alternate 12 ms and 1 ms: setpoint k+1 overtakes setpoint k, which must not act.
  ContourJob job = small_circle_job();
  job.downlink.delay = netsim::make_trace_delay({0.012, 0.001});
  ContourJobRunner runner(job);
  const auto m = runner.run_iteration().metrics;
  // Even-numbered setpoints (12 ms) arrive after odd ones sent later: about half of them, per axis.
  EXPECT_GE(m.stale_setpoints, 2u * 190u);
  EXPECT_LE(m.stale_setpoints, 2u * 201u);
  EXPECT_EQ(m.lost_setpoints, 0u);
  EXPECT_LT(m.e_max_m, 2e-3);  // the loop stays stable on the newest setpoints
}

TEST(ContourJobRunner, LostSetpointsAreCountedAndTheLoopHolds) {
  ContourJob job = small_circle_job();
  job.downlink.loss = netsim::make_bernoulli_loss(0.2);
  ContourJobRunner runner(job);
  const auto m = runner.run_iteration().metrics;
  const double n = 2.0 * 401.0, p = 0.2;
  EXPECT_NEAR(static_cast<double>(m.lost_setpoints), n * p, 4.0 * std::sqrt(n * p * (1 - p)));
  EXPECT_LT(m.e_max_m, 1e-3);
}

TEST(ContourJobRunner, LateFeedbackMissesTheDeadlineAndUsesTheNewestSample) {
  ContourJob job = small_circle_job();
  job.uplink.delay = netsim::make_constant_delay(0.007);  // beyond the 5 ms deadline
  ContourJobRunner runner(job);
  const auto m = runner.run_iteration().metrics;
  EXPECT_EQ(m.deadline_misses, 401u);
  // Computed at the deadline each cycle: tau = 5 ms for every setpoint.
  EXPECT_NEAR(m.tau_mean_s, 0.005, 1e-12);
}

TEST(ContourJobRunner, SameSeedSameResultOtherSeedOtherResult) {
  ContourJob job = small_circle_job("adrc+ilccc");
  job.downlink.delay = netsim::make_uniform_delay(0.0003, 0.0008);
  job.sensor.noise_stddev_m = 1e-7;
  job.iterations = 3;
  const auto a = ContourJobRunner(job).run_all();
  const auto b = ContourJobRunner(job).run_all();
  job.seed = 8;
  const auto c = ContourJobRunner(job).run_all();
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(a[i].metrics.e_sum_m, b[i].metrics.e_sum_m);
    EXPECT_EQ(a[i].metrics.tau_mean_s, b[i].metrics.tau_mean_s);
    EXPECT_NE(a[i].metrics.e_sum_m, c[i].metrics.e_sum_m);
  }
  // Delays differ from one iteration to the next (the network does not repeat).
  EXPECT_NE(a[0].metrics.tau_mean_s, a[1].metrics.tau_mean_s);
}

TEST(ContourJobRunner, AnUnstableLoopIsReportedAndStopsTheRun) {
  // PID cross coupling (kp = 500 on the contour error) cannot take 10 ms of loop delay at h = 5 ms.
  ContourJob job = small_circle_job("adrc+pidccc");
  job.downlink.delay = netsim::make_constant_delay(0.010);
  job.iterations = 5;
  job.record_traces = true;
  ContourJobRunner runner(job);
  const auto records = runner.run_all();
  ASSERT_EQ(records.size(), 1u);  // later iterations are not run
  const auto& m = records[0].metrics;
  EXPECT_TRUE(m.diverged);
  EXPECT_GT(m.diverged_at_s, 0.0);
  EXPECT_LT(m.diverged_at_s, 2.0);
  EXPECT_LE(m.e_max_m, job.divergence_limit_m);
  EXPECT_EQ(records[0].trace.size(), static_cast<std::size_t>(std::llround(m.diverged_at_s / 0.005)));
  // The same loop without delay is stable.
  job.downlink.delay = netsim::make_no_delay();
  EXPECT_FALSE(ContourJobRunner(job).run_iteration().metrics.diverged);
}

// The contour-error limit stops the iteration at the first cycle whose exact contour error
// exceeds it: checked against the same run without the limit, traced cycle by cycle.
TEST(ContourJobRunner, TheContourErrorLimitStopsAtItsFirstCrossingNamingCycleAndAxis) {
  ContourJob free_run = small_circle_job("adrc+pidccc");
  free_run.downlink.delay = netsim::make_constant_delay(0.010);  // unstable: the error grows
  free_run.record_traces = true;
  const auto reference = ContourJobRunner(free_run).run_iteration();
  const double limit = 0.5e-3;
  std::size_t crossing = 0;
  double e_max_before = 0.0;
  while (std::abs(reference.trace.at(crossing).contour_error_m) <= limit) {
    e_max_before = std::max(e_max_before, std::abs(reference.trace[crossing].contour_error_m));
    ++crossing;
  }
  ASSERT_GT(crossing, 10u);

  ContourJob limited = free_run;
  limited.contour_error_limit_m = limit;
  limited.iterations = 3;
  const auto records = ContourJobRunner(limited).run_all();
  ASSERT_EQ(records.size(), 1u);  // later iterations are not run
  const auto& m = records[0].metrics;
  EXPECT_TRUE(m.diverged);
  EXPECT_DOUBLE_EQ(m.diverged_at_s, static_cast<double>(crossing) * 0.005);
  EXPECT_EQ(m.e_max_m, e_max_before);  // the samples before the crossing, bit for bit
  const auto& row = reference.trace[crossing];
  const bool x_worse = std::abs(row.reference_m[0] - row.position_m[0]) >= std::abs(row.reference_m[1] - row.position_m[1]);
  EXPECT_NE(m.stop_reason.find(fmt::format("beyond the limit 0.500 mm at cycle {} ", crossing)), std::string::npos)
      << m.stop_reason;
  EXPECT_NE(m.stop_reason.find(fmt::format("axis {} ", x_worse ? "x" : "y")), std::string::npos) << m.stop_reason;
  EXPECT_NE(m.stop_reason.find(fmt::format("contour error {:.3f} mm", std::abs(row.contour_error_m) * 1e3)),
            std::string::npos)
      << m.stop_reason;

  // A stable run under the same limit is untouched, bit for bit.
  ContourJob stable = small_circle_job("adrc");
  const auto plain = ContourJobRunner(stable).run_iteration().metrics;
  stable.contour_error_limit_m = limit;
  const auto watched = ContourJobRunner(stable).run_iteration().metrics;
  EXPECT_LT(plain.e_max_m, limit);
  EXPECT_EQ(watched.e_max_m, plain.e_max_m);
  EXPECT_EQ(watched.e_sum_m, plain.e_sum_m);
  EXPECT_TRUE(watched.stop_reason.empty());
}

TEST(ContourJobRunner, InvalidJobsNameTheField) {
  ContourJob job = small_circle_job();
  job.sample_period_s = -1.0;
  try {
    ContourJobRunner runner(job);
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("sample_period"), std::string::npos);
  }
  EXPECT_THROW(small_circle_job("adrc+magic"), std::invalid_argument);
  job = small_circle_job();
  job.controller_factory = nullptr;  // a job built without resolving its controller
  EXPECT_THROW(ContourJobRunner{job}, std::invalid_argument);
}

}  // namespace
}  // namespace netmc::sim

namespace netmc::sim {
namespace {

// An adaptive controller's internal estimates reach the trace every cycle and the metrics at the
// end of the iteration; DIARC's mass estimates move from their initial values towards the stage's.
TEST(ContourJobRunner, ControllerEstimatesAreRecordedPerCycleAndAtTheEnd) {
  ContourJob job = testing::thesis_ellipse_job("gtcf-diarc", 2.0);
  job.record_traces = true;
  ContourJobRunner runner(job);
  const auto record = runner.run_iteration();
  const auto& m = record.metrics;
  ASSERT_EQ(m.estimate_names.size(), 10u);  // theta_hat (8) and d_hat_c (2)
  EXPECT_EQ(m.estimate_names[0].name, "M1_hat");
  EXPECT_EQ(m.estimate_names[0].unit, "V/(m/s^2)");
  EXPECT_EQ(m.estimate_names[9].name, "dc2_hat");
  ASSERT_EQ(m.final_estimates.size(), 10u);
  // The last trace row holds the final values; the first the initial estimate (0.1 for M1).
  for (std::size_t i = 0; i < 10; ++i) EXPECT_EQ(record.trace.back().estimates[i], m.final_estimates[i]) << i;
  EXPECT_NEAR(record.trace.front().estimates[0], 0.1, 0.01);
  // The stage's X mass is 0.12 V/(m/s^2): the estimate moved most of the way within 1.8 s.
  EXPECT_GT(m.final_estimates[0], 0.11);
  EXPECT_LT(m.final_estimates[0], 0.13);
  // A controller without internal estimates records none.
  ContourJob plain = testing::small_circle_job("pid");
  EXPECT_TRUE(ContourJobRunner(plain).run_iteration().metrics.estimate_names.empty());
}

}  // namespace
}  // namespace netmc::sim
