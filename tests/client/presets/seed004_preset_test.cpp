// Paper 004's Table 4 (preset seed004): the three controllers on the circle and on the sharp
// angle, full runs (a fraction of a second). The bar: on the circle QFT-CCC < PID-CCC <
// uncoupled, on the sharp angle QFT-CCC best; the gains are the paper's (Tables 1-3, eq. 20).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "client/study_plan.hpp"
#include "server/job/job_builder.hpp"
#include "server/sim/contour_job_runner.hpp"

namespace netmc::cli {
namespace {

// The steady RMS (the whole run: the window opens at the first period) of every job, by label.
std::map<std::string, double> run_all(const StudyPlan& plan) {
  std::map<std::string, double> rms;
  for (const auto& spec : plan.jobs) {
    const auto metrics = sim::ContourJobRunner(job::build_contour_job(spec)).run_iteration().metrics;
    EXPECT_FALSE(metrics.diverged) << spec.name();
    EXPECT_GT(metrics.steady_samples, 0u) << spec.name();
    rms[spec.name()] = metrics.e_rms_steady_m;
  }
  return rms;
}

TEST(Seed004Preset, RunsThePapersSetUp) {
  const StudyPlan plan = make_preset("seed004");
  ASSERT_EQ(plan.jobs.size(), 6u);
  EXPECT_TRUE(plan.steady_metrics);
  for (const auto& spec : plan.jobs) {
    EXPECT_EQ(spec.plant(), "stage004") << spec.name();
    EXPECT_EQ(spec.sample_period_s(), 5e-5) << spec.name();
    EXPECT_EQ(spec.evaluation_start_s(), 5e-5) << spec.name();
    EXPECT_EQ(spec.controller().estimator(), "tangent") << spec.name();  // eq. 3
    // The paper's gains: nothing overridden.
    EXPECT_TRUE(spec.controller().gains().empty()) << spec.name();
    const auto job = job::build_contour_job(spec);
    EXPECT_NEAR(job.duration_s - std::get<std::shared_ptr<const control::ReferenceTrajectory>>(job.reference)->duration_s(), 0.5, 1e-12) << spec.name();  // settling
  }
  const auto& circle = plan.jobs.front().trajectory().circle();
  EXPECT_DOUBLE_EQ(circle.radius_m(), 1.0 / (5.0 * std::numbers::pi));
  EXPECT_EQ(circle.period_s(), 2.0);
  EXPECT_EQ(circle.ramp_s(), 0.2);
  const auto& sharp = plan.jobs.back().trajectory().polyline();
  ASSERT_EQ(sharp.points_size(), 3);
  EXPECT_EQ(sharp.points(2).x_m(), 0.1);
  EXPECT_EQ(sharp.points(2).y_m(), 0.1);
  EXPECT_EQ(sharp.max_speed_m_s(), 0.1);
  EXPECT_EQ(sharp.corner_speed_m_s(), 0.0);  // stops at the corner
}

TEST(Seed004Preset, CrossCouplingOrderingOfTable4) {
  const auto rms = run_all(make_preset("seed004"));
  // Circle: QFT-CCC < PID-CCC < uncoupled (paper: 0.74 < 1.15 < 2.53 um).
  EXPECT_LT(rms.at("circle ffpid+qftccc"), rms.at("circle ffpid+lpccc"));
  EXPECT_LT(rms.at("circle ffpid+lpccc"), rms.at("circle ffpid"));
  // Sharp angle: QFT-CCC best (paper: 4.07 um against 5.66 and 6.06).
  EXPECT_LT(rms.at("sharp ffpid+qftccc"), rms.at("sharp ffpid"));
  EXPECT_LT(rms.at("sharp ffpid+qftccc"), rms.at("sharp ffpid+lpccc"));
  // Sub-micrometre contouring: a wrong sign or a broken discretisation gives mm or divergence.
  for (const auto& [label, value] : rms) EXPECT_LT(value, 1e-6) << label;
}

}  // namespace
}  // namespace netmc::cli
