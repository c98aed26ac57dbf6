// Task-space contouring (thesis ch. 2) on its 10:1 ellipse: x = 0.2 sin 7t, y = 0.02 - 0.02 cos 7t,
// linear-motor plant with friction and cogging the controller does not model, h = 0.2 ms,
// 0.5 um encoder. Both frames must keep the loop stable and contour within a few micrometres
// (the thesis measured 2.2 / 5.7 um RMS on its stage).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "server/sim/contour_job_runner.hpp"
#include "sim_test_support.hpp"

namespace netmc::sim {
namespace {

IterationMetrics run_thesis_ellipse(const std::string& controller) {
  return ContourJobRunner(testing::thesis_ellipse_job(controller, 3.0)).run_iteration().metrics;
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

}  // namespace
}  // namespace netmc::sim
