// Single-axis tracking jobs (thesis ch. 5) through the job layer and the same runner, server loop
// and axis endpoints as the contouring jobs: the group's error is x - x_d, so its RMS and maximum
// are the per-axis tracking metrics (a second computation of the same numbers); the preset
// thesis-dead-zone reproduces Table 5-1's order; bad specs name their field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "client/study_plan.hpp"
#include "client/spec_syntax.hpp"
#include "server/job/controller_gains.hpp"
#include "server/job/job_builder.hpp"
#include "server/sim/contour_job_runner.hpp"

namespace netmc::job {
namespace {

netmc::v1::JobSpec preset_job(const std::string& label) {
  const auto plan = cli::make_preset("thesis-dead-zone");
  const auto it = std::find_if(plan.jobs.begin(), plan.jobs.end(), [&](const auto& j) { return j.name() == label; });
  EXPECT_NE(it, plan.jobs.end()) << label;
  return it == plan.jobs.end() ? plan.jobs.front() : *it;
}

sim::IterationMetrics run(const netmc::v1::JobSpec& spec) {
  sim::ContourJobRunner runner(build_contour_job(spec));
  return runner.run_iteration().metrics;
}

std::string message(const netmc::v1::JobSpec& spec) {
  try {
    build_contour_job(spec);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "no error";
}

TEST(SingleAxisJob, ItsErrorIsTheAxisTrackingErrorAndRepeatsBitForBit) {
  auto spec = preset_job("C3 I");
  spec.set_duration_s(2.0);
  ASSERT_TRUE(is_single_axis_job(spec));
  EXPECT_EQ(group_axis_count(spec), 1u);
  EXPECT_EQ(axis_names(spec), std::vector<std::string>{"x"});
  const auto first = run(spec);
  ASSERT_FALSE(first.diverged);
  ASSERT_EQ(first.tracking_rms_m.size(), 1u);
  // The group's error and the per-axis tracking error are the same samples, summed apart.
  EXPECT_NEAR(first.e_rms_m, first.tracking_rms_m[0], 1e-12 * first.e_rms_m);
  EXPECT_EQ(first.e_max_m, first.tracking_max_m[0]);
  EXPECT_GT(first.e_rms_m, 0.1e-6);
  EXPECT_LT(first.e_rms_m, 100e-6);
  // The controller's estimates reach the iteration's metrics: six parameters and d_c.
  EXPECT_EQ(first.estimate_names.size(), 7u);
  EXPECT_EQ(first.final_estimates.size(), 7u);
  const auto again = run(spec);
  EXPECT_EQ(again.e_rms_m, first.e_rms_m);
  EXPECT_EQ(again.final_estimates, first.final_estimates);
}

// Thesis Table 5-1's order on the preset's own specs (20 s each, judged over the second 10 s):
// C3 within 15 % of C4, both far better than C1 and C2; C5 worst in Exp II.
TEST(SingleAxisJob, DeadZonePresetReproducesTableFiveOnesOrder) {
  const auto plan = cli::make_preset("thesis-dead-zone");
  ASSERT_EQ(plan.jobs.size(), 6u);
  ASSERT_EQ(plan.paper.size(), 6u);
  std::map<std::string, sim::IterationMetrics> m;
  for (const auto& spec : plan.jobs) {
    m[spec.name()] = run(spec);
    EXPECT_FALSE(m[spec.name()].diverged) << spec.name();
  }
  const auto rms = [&](const char* label) { return m.at(label).e_rms_steady_m; };
  EXPECT_LT(std::abs(rms("C3 I") - rms("C4 I")), 0.15 * rms("C4 I"));
  EXPECT_LT(2.0 * rms("C3 I"), rms("C2 I"));
  EXPECT_LT(rms("C2 I"), rms("C1 I"));
  EXPECT_GT(rms("C5 II"), 5.0 * rms("C3 II"));
  EXPECT_GT(m.at("C5 II").e_max_steady_m, m.at("C3 II").e_max_steady_m);
  // Over the whole run C3 carries its first visits to the gap with the nominal break points.
  EXPECT_GT(m.at("C3 I").e_rms_m, 2.0 * rms("C3 I"));
  // Exp II's plant is the symmetric dead zone: C3's left-slope estimate goes towards 3.24, not 3.6.
  const auto& names = m.at("C3 II").estimate_names;
  const auto left = std::find_if(names.begin(), names.end(), [](const auto& n) { return n.name == "ml_hat"; });
  ASSERT_NE(left, names.end());
  EXPECT_LT(m.at("C3 II").final_estimates[static_cast<std::size_t>(left - names.begin())], 3.42);
}

// Thesis section 5.5 as docs/reproductions/thesis.md runs it: each axis of a contouring stage (linmotor, cogging
// included) gets a dead zone; a single-axis axis-diarc-dead-zone run per axis (the spec files in
// tests/data) identifies it; its inverse, with the slopes in the contouring controller's own input
// gain (E^ m times the nominal mass the controller assumes), goes in front of GTCF-SARC on the
// thesis ellipse. Checked against the same run without a dead zone and with the exact inverse.
TEST(SingleAxisJob, IdentifiedDeadZoneInverseRestoresContouring) {
  const auto load = [](const std::string& name) {
    const std::string path = std::string(NETMC_TEST_DATA_DIR) + "/" + name;
    std::ifstream file(path);
    std::stringstream text;
    text << file.rdbuf();
    auto spec = parse_job_spec_json(text.str(), path);
    apply_defaults(spec);  // as netmc sim --spec does
    return spec;
  };
  struct Axis {
    const char* name;
    const char* spec;
    double nominal_mass;  // V/(m/s^2), the thesis's M1, M2 that GTCF-SARC assumes
    double right_break, left_break, right_slope, left_slope;  // the stage's dead zone
  };
  const Axis axes[] = {{"x", "dead_zone_identify_x.json", 0.1, 0.3, -0.25, 0.9, 1.0},
                       {"y", "dead_zone_identify_y.json", 0.55, 0.4, -0.3, 1.0, 0.9}};
  auto contour = preset_job("C3 I");  // replaced below; keeps the helpers in one place
  {
    const auto plan = cli::make_preset("thesis-ellipse");
    contour = *std::find_if(plan.jobs.begin(), plan.jobs.end(), [](const auto& j) { return j.name() == "gtcf-sarc"; });
  }
  contour.set_duration_s(6.0);
  contour.set_evaluation_start_s(2.0);
  const double clean = run(contour).e_rms_steady_m;
  auto identified = contour;
  auto exact = contour;
  for (const Axis& axis : axes) {
    const auto estimates = run(load(axis.spec));
    std::map<std::string, double> e;
    for (std::size_t i = 0; i < estimates.estimate_names.size(); ++i) e[estimates.estimate_names[i].name] = estimates.final_estimates[i];
    // The identified break points within 0.15 V of the stage's: the cogging, which the
    // single-axis model lacks, biases them (Y's left one by 0.13 V).
    EXPECT_NEAR(e["mrbr_hat"] / e["mr_hat"], axis.right_break, 0.15) << axis.name;
    EXPECT_NEAR(e["mlbl_hat"] / e["ml_hat"], axis.left_break, 0.15) << axis.name;
    for (auto* job : {&contour, &identified, &exact}) {
      auto& plant = *job->add_plant_axes();
      plant.set_axis(axis.name);
      for (const auto& [key, value] : {std::pair{"dead_zone_right_v", axis.right_break}, std::pair{"dead_zone_left_v", axis.left_break},
                                       std::pair{"dead_zone_right_slope", axis.right_slope},
                                       std::pair{"dead_zone_left_slope", axis.left_slope}}) {
        auto& parameter = *plant.add_parameters();
        parameter.set_key(key);
        parameter.set_value(value);
      }
    }
    auto& id = *identified.mutable_controller()->add_dead_zone_inverse();
    id.set_axis(axis.name);
    id.mutable_dead_zone()->set_right_break_v(e["mrbr_hat"] / e["mr_hat"]);
    id.mutable_dead_zone()->set_left_break_v(e["mlbl_hat"] / e["ml_hat"]);
    id.mutable_dead_zone()->set_right_slope(e["mr_hat"] * axis.nominal_mass);
    id.mutable_dead_zone()->set_left_slope(e["ml_hat"] * axis.nominal_mass);
    auto& truth = *exact.mutable_controller()->add_dead_zone_inverse();
    truth.set_axis(axis.name);
    truth.mutable_dead_zone()->set_right_break_v(axis.right_break);
    truth.mutable_dead_zone()->set_left_break_v(axis.left_break);
    truth.mutable_dead_zone()->set_right_slope(axis.right_slope);
    truth.mutable_dead_zone()->set_left_slope(axis.left_slope);
  }
  const double none = run(contour).e_rms_steady_m;
  const double with_identified = run(identified).e_rms_steady_m;
  const double with_exact = run(exact).e_rms_steady_m;
  EXPECT_NEAR(with_exact, clean, 0.1 * clean);  // the exact inverse removes the dead zone
  EXPECT_GT(none, 2.5 * with_exact);
  EXPECT_LT(with_identified, 1.3 * with_exact);
}

TEST(SingleAxisJob, BadSpecsNameTheField) {
  auto spec = preset_job("C3 I");
  spec.mutable_controller()->set_name("adrc");
  EXPECT_EQ(message(spec).rfind("controller:", 0), 0u) << message(spec);
  spec = preset_job("C3 I");
  spec.mutable_trajectory()->mutable_halt()->set_at_s(1.0);
  EXPECT_EQ(message(spec).rfind("trajectory.multi_sine:", 0), 0u) << message(spec);
  spec = preset_job("C3 I");
  spec.mutable_trajectory()->mutable_multi_sine()->mutable_terms(0)->set_frequency_hz(-1.0);
  EXPECT_EQ(message(spec).rfind("trajectory.multi_sine.terms[0].frequency_hz:", 0), 0u) << message(spec);
  spec = preset_job("C3 I");
  for (int i = 0; i < 17; ++i) *spec.mutable_trajectory()->mutable_multi_sine()->add_terms() = spec.trajectory().multi_sine().terms(0);
  EXPECT_EQ(message(spec).rfind("trajectory.multi_sine.terms:", 0), 0u) << message(spec);
  spec = preset_job("C3 I");
  spec.mutable_trajectory()->mutable_multi_sine()->set_duration_s(0.0);
  EXPECT_EQ(message(spec).rfind("trajectory.multi_sine.duration_s:", 0), 0u) << message(spec);
  spec = preset_job("C3 I");
  spec.mutable_initial_position()->set_x_m(0.1);
  EXPECT_EQ(message(spec).rfind("initial_position:", 0), 0u) << message(spec);
  spec = preset_job("C3 I");
  spec.add_axes("a");
  spec.add_axes("b");
  EXPECT_EQ(message(spec).rfind("axes: a 1-axis job needs 1 axis name", 0), 0u) << message(spec);
  // A law of two axes asked for one: refused, naming the laws that run one axis and how.
  netmc::v1::JobSpec planar = cli::make_preset("seed001").jobs.front();
  planar.add_axes("x");
  EXPECT_EQ(message(planar),
            "axes: a 2-axis job needs 2 axis names, got 1; a single axis runs a single-axis law on a multi-sine "
            "reference (axis-diarc, axis-diarc+nominal-inverse, axis-diarc+exact-inverse, axis-diarc-dead-zone, "
            "axis-avsc), e.g. --axes x --preset thesis-dead-zone --controller axis-diarc");
  spec = preset_job("C3 I");
  spec.set_plant("linmotor");  // a contouring controller's plant works; a planar controller does not
  spec.mutable_controller()->set_name("gtcf-sarc");
  EXPECT_EQ(message(spec).rfind("controller:", 0), 0u) << message(spec);
  spec = preset_job("C4 I");
  job::set_gain(*spec.mutable_controller(), "axis_diarc", "right_slope", -1.0);
  EXPECT_EQ(message(spec).rfind("controller.gains.axis_diarc.right_slope: expected a positive finite number", 0), 0u)
      << message(spec);
}

TEST(SingleAxisJob, CommandLineFormIsTheSpecsForm) {
  const auto t = cli::parse_trajectory("multi-sine:terms=80mm/0.5/-1.5;70um/0.4/0,offset=210mm,duration=20s,period=10s");
  ASSERT_TRUE(t.has_multi_sine());
  const auto& m = t.multi_sine();
  ASSERT_EQ(m.terms_size(), 2);
  EXPECT_DOUBLE_EQ(m.terms(0).amplitude_m(), 0.08);
  EXPECT_DOUBLE_EQ(m.terms(0).frequency_hz(), 0.5);
  EXPECT_DOUBLE_EQ(m.terms(0).phase_rad(), -1.5);
  EXPECT_DOUBLE_EQ(m.terms(1).amplitude_m(), 70e-6);
  EXPECT_DOUBLE_EQ(m.offset_m(), 0.21);
  EXPECT_DOUBLE_EQ(m.duration_s(), 20.0);
  EXPECT_DOUBLE_EQ(m.period_s(), 10.0);
  // --dead-zone-inverse AXIS:b_r=..,b_l=..[,m_r=..,m_l=..] writes controller.dead_zone_inverse.
  auto job = preset_job("C3 I");
  cli::parse_dead_zone_inverse("x:b_r=0.3,b_l=-0.25,m_r=0.9", job);
  ASSERT_EQ(job.controller().dead_zone_inverse_size(), 1);
  EXPECT_EQ(job.controller().dead_zone_inverse(0).axis(), "x");
  EXPECT_DOUBLE_EQ(job.controller().dead_zone_inverse(0).dead_zone().left_break_v(), -0.25);
  EXPECT_DOUBLE_EQ(job.controller().dead_zone_inverse(0).dead_zone().left_slope(), 1.0);
  EXPECT_NO_THROW(build_contour_job(job));
  for (const char* bad : {"z:b_r=0.3,b_l=-0.2", "x:b_r=0.3", "x:b_r=0.3,b_l=-0.2,slope=1", "x0.3"}) {
    auto copy = preset_job("C3 I");
    EXPECT_THROW(cli::parse_dead_zone_inverse(bad, copy), std::invalid_argument) << bad;
  }
  cli::parse_dead_zone_inverse("x:b_r=0.3,b_l=0.2", job);  // b_l must be <= 0: refused when built
  EXPECT_EQ(message(job).rfind("controller.dead_zone_inverse[0].dead_zone.left_break_v:", 0), 0u) << message(job);
  for (const char* bad : {"multi-sine:terms=80mm/0.5,duration=1s", "multi-sine:duration=1s",
                          "multi-sine:terms=80mm/0.5/0/1,duration=1s", "multi-sine:terms=80mm/x/0,duration=1s"}) {
    try {
      cli::parse_trajectory(bad);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("--trajectory"), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace netmc::job
