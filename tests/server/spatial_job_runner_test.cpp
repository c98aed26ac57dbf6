// Three-axis jobs (thesis ch. 6) through the job layer: GTCF-SARC on a tilted circle behind the
// same axis endpoints as two-axis jobs. Checked against the library's own closed loop
// (tests/control/spatial_gtcf_test.cpp: 1.73 um RMS without network or drive limit), against
// itself (determinism), and under delay, where it must degrade in order and fail at 2 ms as
// its two-axis parent does on the thesis ellipse.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "server/job/job_builder.hpp"
#include "server/sim/spatial_job_runner.hpp"

namespace netmc::job {
namespace {

netmc::v1::JobSpec tilted_circle_spec() {
  netmc::v1::JobSpec spec;
  auto& c = *spec.mutable_trajectory()->mutable_spatial_circle();
  c.set_center_x_m(0.10);
  c.set_center_y_m(0.10);
  c.set_center_z_m(0.05);
  c.set_radius_m(0.05);
  c.set_normal_x(-1.0);
  c.set_normal_y(1.0);
  c.set_normal_z(0.5);
  c.set_start_z(1.0);
  c.set_period_s(2.0 * std::numbers::pi / 4.0);
  c.set_revolutions(4.0);
  spec.set_plant("linmotor");
  spec.mutable_controller()->set_name("gtcf-sarc");
  spec.set_sample_period_s(2e-4);
  spec.mutable_sensor()->set_resolution_m(0.5e-6);
  spec.set_iterations(1);
  spec.set_seed(3);
  return spec;
}

sim::SpatialIterationMetrics run(const netmc::v1::JobSpec& spec) {
  return sim::SpatialJobRunner(build_spatial_job(spec)).run();
}

TEST(SpatialJob, ContoursLikeTheLibraryLoopAndRepeatsBitForBit) {
  const auto spec = tilted_circle_spec();
  ASSERT_TRUE(is_spatial_job(spec));
  const auto first = run(spec);
  ASSERT_FALSE(first.diverged);
  // The library loop measured 1.73 / 4.15 um; other sensor seeds, same physics.
  EXPECT_LT(first.e_rms_steady_m, 3e-6);
  EXPECT_GT(first.e_rms_steady_m, 0.5e-6);
  EXPECT_LT(first.e_max_steady_m, 10e-6);
  for (const double u : first.command_rms_steady) {
    EXPECT_GT(u, 0.05);
    EXPECT_LT(u, 2.0);
  }
  const auto again = run(spec);
  EXPECT_EQ(again.e_rms_steady_m, first.e_rms_steady_m);
  EXPECT_EQ(again.e_max_m, first.e_max_m);
  EXPECT_EQ(first.tau_mean_s, 0.0);
}

TEST(SpatialJob, DegradesWithDelayAndFailsAtTwoMilliseconds) {
  auto spec = tilted_circle_spec();
  spec.set_command_limit(8.0);
  const auto none = run(spec);
  auto& uniform = *spec.mutable_downlink()->mutable_delay()->mutable_uniform();
  uniform.set_min_s(0.1e-3);
  uniform.set_max_s(0.5e-3);
  const auto short_delay = run(spec);
  spec.mutable_downlink()->mutable_delay()->set_constant_s(2e-3);
  const auto long_delay = run(spec);
  EXPECT_NEAR(short_delay.tau_mean_s, 0.3e-3, 0.02e-3);
  EXPECT_GT(short_delay.e_rms_steady_m, 1.1 * none.e_rms_steady_m);
  EXPECT_LT(short_delay.e_rms_steady_m, 10e-6);
  EXPECT_GT(long_delay.e_rms_steady_m, 20.0 * none.e_rms_steady_m);
  EXPECT_NEAR(long_delay.tau_max_s, 2e-3, 1e-9);
}

TEST(SpatialJob, BadSpecsNameTheFieldAndTheTwoAxisServerRefusesThem) {
  const auto message = [](const netmc::v1::JobSpec& spec) {
    try {
      build_spatial_job(spec);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  auto spec = tilted_circle_spec();
  spec.mutable_controller()->set_name("ltcf-sarc");
  EXPECT_EQ(message(spec).rfind("controller:", 0), 0u) << message(spec);
  spec = tilted_circle_spec();
  spec.mutable_trajectory()->mutable_spatial_circle()->set_radius_m(-1.0);
  EXPECT_EQ(message(spec).rfind("trajectory.spatial_circle:", 0), 0u) << message(spec);
  spec = tilted_circle_spec();
  spec.mutable_trajectory()->mutable_spatial_circle()->set_normal_x(0.0);
  spec.mutable_trajectory()->mutable_spatial_circle()->set_normal_y(0.0);
  spec.mutable_trajectory()->mutable_spatial_circle()->set_normal_z(0.0);
  EXPECT_EQ(message(spec).rfind("trajectory.spatial_circle:", 0), 0u) << message(spec);
  spec = tilted_circle_spec();
  spec.set_iterations(5);
  EXPECT_EQ(message(spec).rfind("iterations:", 0), 0u) << message(spec);
  spec = tilted_circle_spec();
  spec.mutable_uplink()->mutable_delay()->set_constant_s(1e-3);
  EXPECT_EQ(message(spec).rfind("uplink:", 0), 0u) << message(spec);
  try {
    build_contour_job(tilted_circle_spec());
    ADD_FAILURE() << "the two-axis builder accepted a three-axis contour";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("spatial_circle"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace netmc::job
