// Task-space contouring (thesis ch. 2) on its 10:1 ellipse: x = 0.2 sin 7t, y = 0.02 - 0.02 cos 7t,
// linear-motor plant with friction and cogging the controller does not model, h = 0.2 ms,
// 0.5 um encoder. Both frames must keep the loop stable and contour within a few micrometres
// (the thesis measured 2.2 / 5.7 um RMS on its stage).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/ellipse_trajectory.hpp"
#include "plant/plant_catalog.hpp"
#include "server/sim/contour_job_runner.hpp"

namespace netmc::sim {
namespace {

IterationMetrics run_thesis_ellipse(const std::string& controller) {
  ContourJob job;
  control::EllipseParameters ellipse;
  ellipse.center = {0.0, 0.02};
  ellipse.semi_axis_x_m = 0.2;
  ellipse.semi_axis_y_m = 0.02;
  ellipse.period_s = 2.0 * std::numbers::pi / 7.0;
  ellipse.start_angle_rad = -std::numbers::pi / 2.0;
  ellipse.revolutions = 3.0;
  job.trajectory = std::make_shared<control::EllipseTrajectory>(ellipse);
  auto plants = plant::make_plant_set("linmotor", 2);
  for (auto& axis : plants.axes) job.axes.emplace_back(std::move(axis));
  job.plant_name = "linmotor";
  job.controller_name = controller;
  job.sample_period_s = 2e-4;
  job.sensor.resolution_m = 0.5e-6;
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

}  // namespace
}  // namespace netmc::sim
