// Task-space contouring (thesis ch. 2) on its 10:1 ellipse: x = 0.2 sin 7t, y = 0.02 - 0.02 cos 7t,
// linear-motor plant with friction and cogging the controller does not model, h = 0.2 ms,
// 0.5 um encoder. Both frames must keep the loop stable and contour within a few micrometres
// (the thesis measured 2.2 / 5.7 um RMS on its stage).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/trajectory/halted_trajectory.hpp"
#include "server/sim/contour_job_runner.hpp"
#include "sim_test_support.hpp"

namespace netmc::sim {
namespace {

// halt_at_s < 0: no halt (case C); otherwise case D's 4 ms halt at that time, command limited
// to the thesis DAC's 10 V.
IterationMetrics run_thesis_ellipse(const std::string& controller, double halt_at_s = -1.0) {
  ContourJob job = testing::thesis_ellipse_job(controller, 3.0);
  if (halt_at_s >= 0.0) {
    job.reference = std::make_shared<control::HaltedTrajectory>(
        std::get<std::shared_ptr<const control::ReferenceTrajectory>>(job.reference), halt_at_s, 0.004);
    job.command_limit = 10.0;
    testing::use_controller(job, controller);  // for the halted reference
  }
  return ContourJobRunner(job).run_iteration().metrics;
}

TEST(SarcStudy, BothTaskFramesContourTheThesisEllipseWithinMicrometres) {
  const auto gtcf = run_thesis_ellipse("gtcf-sarc");
  const auto ltcf = run_thesis_ellipse("ltcf-sarc");
  ASSERT_FALSE(gtcf.diverged);
  ASSERT_FALSE(ltcf.diverged);
  // 1.4 m/s at 9.8 m/s^2. A velocity estimate that lags half a period (plain backward
  // difference) gave 3.4 / 4.9 um RMS here: these bounds catch that regression.
  for (const auto* m : {&gtcf, &ltcf}) {
    EXPECT_LT(m->e_rms_steady_m, 2.5e-6);  // after the first two periods
    EXPECT_LT(m->e_max_steady_m, 8e-6);
  }
}

// Case D: the reference stops dead for 4 ms on the ellipse's flat side (x = 0, 1.4 m/s), so the
// stage overshoots the halted point by millimetres along the path. LTCF measures the contour
// error at the halted desired point and its frame turns with it; GTCF measures it from the
// contour itself. The thesis's stage: 68.5 against 23.4 um max; simulated: 22.4 against 4.3 um.
TEST(SarcStudy, SuddenHaltCostsTheLocalFrameMoreThanTheGlobalFrame) {
  const double flat_side_s = 2.0 * std::numbers::pi / 7.0 * 2.5;  // x = 0 again, moving at 1.4 m/s
  const auto gtcf = run_thesis_ellipse("gtcf-sarc", flat_side_s);
  const auto ltcf = run_thesis_ellipse("ltcf-sarc", flat_side_s);
  ASSERT_FALSE(gtcf.diverged);
  ASSERT_FALSE(ltcf.diverged);
  EXPECT_LT(gtcf.e_max_steady_m, 10e-6);
  EXPECT_GT(ltcf.e_max_steady_m, 2.0 * gtcf.e_max_steady_m);
}

// Case C with a soft tangential loop: the local frame measures the contour error at the desired
// point's tangent, off by about kappa e_t^2 / 2 and by the frame's turning (alpha' e_t), both
// growing with the tangential error e_t. With the thesis gains e_t stays near 5 um and the frames
// agree within 10 %; with Lambda_m = 2, K_m = 5 (e_t 30-55 um RMS) GTCF must beat LTCF by the
// thesis's margin (GTCF <= 0.6 LTCF; thesis 0.39, measured here over 6 s: see docs/reproductions/thesis.md).
TEST(SarcStudy, LocalFrameLosesToGlobalFrameWhenTheTangentialErrorIsLarge) {
  const auto soft = [](const std::string& controller) {
    ContourJob job = testing::thesis_ellipse_job(controller, 7.0);
    netmc::v1::ControllerSpec spec;
    job::set_gain(spec, "task_space", "lambda_m", 2.0);
    job::set_gain(spec, "task_space", "k_m", 5.0);
    testing::use_controller(job, controller, spec);
    return ContourJobRunner(job).run_iteration().metrics;
  };
  const auto gtcf_soft = soft("gtcf-sarc");
  const auto ltcf_soft = soft("ltcf-sarc");
  ASSERT_FALSE(gtcf_soft.diverged);
  ASSERT_FALSE(ltcf_soft.diverged);
  EXPECT_LT(gtcf_soft.e_rms_steady_m, 0.6 * ltcf_soft.e_rms_steady_m);

  const auto gtcf = run_thesis_ellipse("gtcf-sarc");
  const auto ltcf = run_thesis_ellipse("ltcf-sarc");
  EXPECT_NEAR(gtcf.e_rms_steady_m / ltcf.e_rms_steady_m, 1.0, 0.1);
}

}  // namespace
}  // namespace netmc::sim
