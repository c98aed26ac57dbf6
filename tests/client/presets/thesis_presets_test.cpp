// The thesis presets (paper 000) run closed loop: every GTCF controller of thesis-ellipse,
// thesis-circle (cases A and B) and thesis-darc stays stable and contours within a few
// micrometres, on shortened runs. Case B starts 6 cm off the desired point: the initialization
// filter keeps rc - r_ci within the thesis's 70 um and the command within the 8 V drive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "client/study_plan.hpp"
#include "control/task_space/task_space_cogging_darc.hpp"
#include "control/task_space/task_space_diarc.hpp"
#include "plant/plant_catalog.hpp"
#include "tests/control/thesis_model_support.hpp"
#include "server/job/job_builder.hpp"
#include "server/sim/contour_job_runner.hpp"

namespace netmc::cli {
namespace {

struct Shortened {
  double duration_s;
  double evaluation_start_s;
};

sim::IterationRecord run(const netmc::v1::JobSpec& spec, Shortened length) {
  auto job = job::build_contour_job(spec);
  job.duration_s = length.duration_s;
  job.evaluation_start_s = length.evaluation_start_s;
  job.record_traces = true;
  return sim::ContourJobRunner(job).run_iteration();
}

// The plan's job labelled `label` (a failure, and the first job, when there is none).
netmc::v1::JobSpec job_named(const StudyPlan& plan, const std::string& label) {
  const auto it = std::find_if(plan.jobs.begin(), plan.jobs.end(), [&](const auto& j) { return j.name() == label; });
  EXPECT_NE(it, plan.jobs.end()) << label;
  return it == plan.jobs.end() ? plan.jobs.front() : *it;
}

void expect_contours_within(const StudyPlan& plan, const std::string& label, Shortened length,
                            double rms_bound_m, double max_bound_m) {
  const auto job = std::find_if(plan.jobs.begin(), plan.jobs.end(),
                                [&](const auto& j) { return j.name() == label; });
  ASSERT_NE(job, plan.jobs.end()) << label;
  const auto m = run(*job, length).metrics;
  ASSERT_FALSE(m.diverged) << label << " at " << m.diverged_at_s;
  EXPECT_GT(m.e_rms_steady_m, 0.0) << label;  // the window is not empty
  EXPECT_LT(m.e_rms_steady_m, rms_bound_m) << label;
  EXPECT_LT(m.e_max_steady_m, max_bound_m) << label;
}

// The full runs measure 1.4-2.4 um RMS and 3.7-5.0 um max (docs/reproductions/thesis.md); the bounds are about twice
// that and far below what a wrong sign or a lost adaptation gives (mm, or unstable).
TEST(ThesisPresets, GtcfControllersContourTheEllipseAndCaseAStably) {
  const StudyPlan ellipse = make_preset("thesis-ellipse");
  for (const char* label : {"gtcf-sarc", "gtcf-darc"}) expect_contours_within(ellipse, label, {3.0, 1.5}, 4e-6, 12e-6);
  const StudyPlan circle = make_preset("thesis-circle");
  for (const char* label : {"gtcf-sarc A", "gtcf-darc A"}) expect_contours_within(circle, label, {3.0, 1.5}, 5e-6, 12e-6);
  const StudyPlan darc = make_preset("thesis-darc");
  for (const char* label : {"gtcf-darc", "gtcf-diarc"}) expect_contours_within(darc, label, {4.0, 2.0}, 4e-6, 12e-6);
}

TEST(ThesisPresets, CaseBStartsFromRestThroughTheInitializationFilter) {
  const StudyPlan circle = make_preset("thesis-circle");
  for (const char* label : {"gtcf-sarc B", "gtcf-darc B"}) {
    const auto job = std::find_if(circle.jobs.begin(), circle.jobs.end(),
                                  [&](const auto& j) { return j.name() == label; });
    ASSERT_NE(job, circle.jobs.end()) << label;
    ASSERT_EQ(job->controller().gains().at("task_space").choices().at("initialization_filter"), "on");
    const auto record = run(*job, {3.0, 2.0});
    ASSERT_FALSE(record.metrics.diverged) << label;
    // The stage starts 1 cm outside the circle (exact contour error 10 mm at t = 0).
    EXPECT_NEAR(record.trace.front().contour_error_m, 0.01, 1e-9);
    double filtered_error = 0.0, command = 0.0;
    for (const auto& row : record.trace) {
      filtered_error = std::max(filtered_error, std::abs(row.contour_error_estimate_m));  // rc - r_ci
      command = std::max({command, std::abs(row.command[0]), std::abs(row.command[1])});
    }
    EXPECT_LT(filtered_error, 70e-6) << label;  // thesis: < 70 um in the transient (measured 4-5 um)
    EXPECT_LT(command, 8.0) << label;           // within the linear range of the drive
    EXPECT_LT(record.metrics.e_rms_steady_m, 5e-6) << label;
    EXPECT_LT(record.metrics.e_max_steady_m, 15e-6) << label;
  }
}

// Thesis ch. 3 states that DIARC's estimates converge to the offline-identified values and
// DARC's do not. On the linmotor stage (M = 0.12 / 0.55, B = 0.3 / 0.4, A = 0.1 / 0.15, plus
// cogging the model lacks), Exp I for 10 s from rest, 0.5 um encoder.
template <typename Controller>
control::ParameterVector estimate_after_exp_i(Controller& controller) {
  const control::EllipseTrajectory ellipse = control::thesis_support::exp_i_ellipse(10.0 * 4.0 / (2.0 * std::numbers::pi));
  auto stage = plant::make_plant_set("linmotor", 2);
  const double h = 2e-4;
  const auto encoder = [](double x) { return std::round(x / 0.5e-6) * 0.5e-6; };
  controller.begin_iteration(Eigen::Vector2d::Zero(), 0);
  for (std::size_t k = 0; k <= 50000; ++k) {
    const Eigen::Vector2d q(encoder(stage.axes[0]->position()), encoder(stage.axes[1]->position()));
    const auto out = controller.step(k, ellipse.sample(static_cast<double>(k) * h), q);
    for (int i = 0; i < 2; ++i) stage.axes[static_cast<std::size_t>(i)]->advance(h, out.command[i]);
  }
  return controller.parameter_estimate();
}

TEST(ThesisPresets, DiarcEstimatesApproachTheStageWhereDarcsDoNot) {
  const auto frame = control::make_task_frame(control::thesis_support::exp_i_ellipse(1.0));
  control::TaskSpaceDiarc diarc(control::DiarcGains{}, 2e-4, frame);
  control::TaskSpaceDarc darc(control::DarcGains{}, 2e-4, frame);
  // Measured: DIARC 0.123 0.554 0.299 0.360 0.100 0.161 -0.003 0.001 (B2 still rising from 0.3);
  // DARC 0.250 0.566 0.311 0.300 0.122 0.150 -0.402 -0.074 (M1 on its face, offsets chasing
  // the cogging).
  const auto indirect = estimate_after_exp_i(diarc);
  EXPECT_NEAR(indirect[0], 0.12, 0.01);
  EXPECT_NEAR(indirect[1], 0.55, 0.02);
  EXPECT_NEAR(indirect[2], 0.3, 0.03);
  EXPECT_NEAR(indirect[4], 0.1, 0.01);
  EXPECT_NEAR(indirect[5], 0.15, 0.02);
  EXPECT_NEAR(indirect[6], 0.0, 0.02);
  EXPECT_NEAR(indirect[7], 0.0, 0.02);
  const auto direct = estimate_after_exp_i(darc);
  EXPECT_GT(std::abs(direct[0] - 0.12), 0.05);
}

}  // namespace
}  // namespace netmc::cli

namespace netmc::cli {
namespace {

// Tables 3-1/3-2's sets through job overrides: Set2 adds 0.07 V/(m/s^2) to both masses (the 5 kg
// payload), Set3 puts 0.8 V on Y from 2.2 to 5.2 s. Set3's step shows in the error exactly
// while it is on (the thesis: spikes at step on and off), and DIARC's fast disturbance estimate
// takes most of it over.
TEST(ThesisPresets, SetsTwoAndThreeChangeOnlyThePlant) {
  const StudyPlan plan = make_preset("thesis-darc-sets");
  ASSERT_EQ(plan.jobs.size(), 18u);
  const auto find = [&](const std::string& label) { return job_named(plan, label); };
  const auto set2 = job::build_contour_job(find("gtcf-diarc I Set2"));
  EXPECT_NE(set2.axes[0]->describe().find("M=0.19"), std::string::npos) << set2.axes[0]->describe();
  EXPECT_NE(set2.axes[1]->describe().find("M=0.62"), std::string::npos) << set2.axes[1]->describe();
  const auto set3_spec = find("gtcf-diarc I Set3");
  const auto set1 = run(find("gtcf-diarc I Set1"), {3.0, 2.0}).metrics;
  const auto set3 = run(set3_spec, {3.0, 2.0}).metrics;
  // Measured over 2-3 s: max 3.8 um without the step, 31 um with it (the on-switch at 2.2 s).
  EXPECT_LT(set1.e_max_steady_m, 6e-6);
  EXPECT_GT(set3.e_max_steady_m, 20e-6);
  EXPECT_LT(set3.e_max_steady_m, 60e-6);
  const auto before = run(set3_spec, {2.15, 2.0}).metrics;  // the step is not on yet
  EXPECT_LT(before.e_max_steady_m, 6e-6);
}

}  // namespace
}  // namespace netmc::cli

namespace netmc::cli {
namespace {

// Thesis ch. 4: with the cogging harmonics adapting (C2), their estimates find the stage's
// cogging (plant/models/linmotor.cpp: X (0.05, 0.03), (0.02, -0.01), (0.01, 0.01) V; Y (0.04, -0.02),
// (0.03, 0.02), (0.015, -0.01) V) within 0.01 V on Exp II, and the contour error drops.
TEST(ThesisPresets, CoggingEstimatesFindTheStagesCogging) {
  const StudyPlan plan = make_preset("thesis-cogging");
  ASSERT_EQ(plan.jobs.size(), 12u);
  const auto find = [&](const std::string& label) { return job_named(plan, label); };
  const auto c2 = run(find("C2 II Set1"), {10.0, 2.0}).metrics;
  const auto c1 = run(find("C1 II Set1"), {10.0, 2.0}).metrics;
  ASSERT_EQ(c2.final_estimates.size(), 20u);
  const double truth[12] = {0.05, 0.03, 0.02, -0.01, 0.01, 0.01, 0.04, -0.02, 0.03, 0.02, 0.015, -0.01};
  for (int i = 0; i < 12; ++i) {
    EXPECT_NEAR(c2.final_estimates[6 + static_cast<std::size_t>(i)], truth[i], 0.01) << c2.estimate_names[6 + static_cast<std::size_t>(i)].name;
    EXPECT_EQ(c1.final_estimates[6 + static_cast<std::size_t>(i)], 0.0);  // C1 does not adapt them
  }
  // Measured: 2.01 against 2.74 um (-27 %; thesis -28 %).
  EXPECT_LT(c2.e_rms_steady_m, 0.85 * c1.e_rms_steady_m);
}

}  // namespace
}  // namespace netmc::cli

namespace netmc::control {
namespace {

TEST(CoggingDarc, RegressorHoldsTheHarmonicsOfEachAxisPosition) {
  const CoggingDarcGains gains;
  const Eigen::Vector2d position(0.0123, -0.0456);
  const auto phi = cogging_darc_regressor(gains, {1.0, 2.0}, {0.1, -0.2}, {0.3, -0.4}, position);
  const double k = 2.0 * std::numbers::pi / 0.05;
  EXPECT_EQ(phi(0, 0), 1.0);
  EXPECT_EQ(phi(1, 1), 2.0);
  EXPECT_EQ(phi(0, 2), 0.1);
  EXPECT_NEAR(phi(1, 5), 2.0 / std::numbers::pi * std::atan(9000.0 * -0.4), 1e-15);  // desired velocity
  EXPECT_NEAR(phi(0, 6), std::sin(k * 1 * position.x()), 1e-15);
  EXPECT_NEAR(phi(0, 11), std::cos(k * 3 * position.x()), 1e-15);
  EXPECT_NEAR(phi(1, 14), std::sin(k * 6 * position.y()), 1e-15);
  EXPECT_NEAR(phi(1, 17), std::cos(k * 12 * position.y()), 1e-15);
  EXPECT_EQ(phi(0, 12), 0.0);  // X's row has no Y harmonics
  EXPECT_EQ(phi(0, 18), -1.0);
  EXPECT_EQ(phi(1, 19), -1.0);
}

}  // namespace
}  // namespace netmc::control
