// Every number of a job's reference within a physical range (docs/operations/hostile-networks-and-clients.md, "Job spec limits"): absurd
// values are refused with one message naming the field and the range, before anything runs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "server/job/job_builder.hpp"
#include "tests/server/job_build_error.hpp"

namespace netmc::job {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A spec of `trajectory` (JSON) at h = 5 ms, otherwise the defaults.
netmc::v1::JobSpec spec_of(const std::string& trajectory, const std::string& controller = "adrc") {
  auto spec = parse_job_spec_json(R"({"trajectory": )" + trajectory + R"(, "controller": {"name": ")" + controller +
                                      R"("}, "sample_period_s": 0.005})",
                                  "test");
  apply_defaults(spec);
  return spec;
}

netmc::v1::JobSpec circle() {
  return spec_of(R"({"circle": {"radius_m": 0.01, "center_x_m": 0.05, "center_y_m": 0.05, "period_s": 8}})");
}

TEST(ReferenceLimits, TheProbesCircleIsRefusedNamingTheFieldAndRange) {
  auto spec = circle();
  spec.mutable_trajectory()->mutable_circle()->set_period_s(1e-300);
  EXPECT_EQ(error_of(spec),
            "trajectory.circle.period_s: expected a number in [0.05, 1e+06] s (10 sample periods of 0.005 s or "
            "more), got 1e-300");
  spec = circle();
  spec.mutable_trajectory()->mutable_circle()->set_center_x_m(1e308);
  EXPECT_EQ(error_of(spec),
            "trajectory.circle.center_x_m: expected a number in [-10, 10] m (the workspace), got 1e+308");
}

TEST(ReferenceLimits, NanAndInfinityAreRefusedInEveryCircleField) {
  for (const double bad : {kNan, kInf, -kInf, 1e308, -1e308}) {
    auto spec = circle();
    spec.mutable_trajectory()->mutable_circle()->set_center_y_m(bad);
    EXPECT_EQ(error_of(spec).rfind("trajectory.circle.center_y_m: expected", 0), 0u) << bad;
    spec = circle();
    spec.mutable_trajectory()->mutable_circle()->set_radius_m(bad);
    EXPECT_EQ(error_of(spec).rfind("trajectory.circle.radius_m: expected a number in [1e-06, 10] m", 0), 0u) << bad;
    spec = circle();
    spec.mutable_trajectory()->mutable_circle()->set_period_s(bad);
    EXPECT_EQ(error_of(spec).rfind("trajectory.circle.period_s: expected", 0), 0u) << bad;
    spec = circle();
    spec.mutable_trajectory()->mutable_circle()->set_start_angle_rad(bad);
    EXPECT_EQ(error_of(spec).rfind("trajectory.circle.start_angle_rad: expected", 0), 0u) << bad;
    spec = circle();
    spec.mutable_trajectory()->mutable_circle()->set_revolutions(bad);
    EXPECT_EQ(error_of(spec).rfind("trajectory.circle.revolutions: expected", 0), 0u) << bad;
  }
}

TEST(ReferenceLimits, JsonNanAndInfinityAreRefusedToo) {
  // protobuf's JSON mapping reads "NaN" and "Infinity" as doubles: the range check sees them.
  const auto nan_spec = spec_of(R"({"circle": {"radius_m": "NaN", "period_s": 8}})");
  EXPECT_EQ(error_of(nan_spec), "trajectory.circle.radius_m: expected a number in [1e-06, 10] m, got nan");
  const auto inf_spec = spec_of(R"({"circle": {"radius_m": 0.01, "period_s": "Infinity"}})");
  EXPECT_EQ(error_of(inf_spec).rfind("trajectory.circle.period_s: expected a number in [0.05, 1e+06] s", 0), 0u)
      << error_of(inf_spec);
}

TEST(ReferenceLimits, ThePeriodBoundFollowsTheSamplePeriod) {
  auto spec = circle();
  spec.mutable_trajectory()->mutable_circle()->set_period_s(0.05);  // exactly 10 samples of 5 ms
  EXPECT_EQ(error_of(spec), "");
  spec.mutable_trajectory()->mutable_circle()->set_period_s(0.0499);
  EXPECT_NE(error_of(spec).find("circle.period_s"), std::string::npos);
  spec.set_sample_period_s(0.001);  // 49.9 samples of 1 ms
  EXPECT_EQ(error_of(spec), "");
}

TEST(ReferenceLimits, EveryShapeBoundsItsNumbers) {
  struct Case {
    std::string trajectory;
    std::string field;
  };
  const Case cases[] = {
      {R"({"ellipse": {"semi_axis_x_m": 1e308, "semi_axis_y_m": 0.01, "period_s": 8}})", "ellipse.semi_axis_x_m"},
      {R"({"ellipse": {"semi_axis_x_m": 0.02, "semi_axis_y_m": 0.01, "period_s": 1e-300}})", "ellipse.period_s"},
      {R"({"ellipse": {"semi_axis_x_m": 0.02, "semi_axis_y_m": 0.01, "feed": {"feed_m_s": 1e308,
          "max_normal_acceleration_m_s2": 1}}})", "ellipse.feed.feed_m_s"},
      {R"({"ellipse": {"semi_axis_x_m": 0.02, "semi_axis_y_m": 0.01, "feed": {"feed_m_s": 0.01,
          "max_normal_acceleration_m_s2": "Infinity"}}})", "ellipse.feed.max_normal_acceleration_m_s2"},
      {R"({"line": {"x0_m": 0, "y0_m": 0, "x1_m": 1e308, "y1_m": 0, "duration_s": 1}})", "line.x1_m"},
      {R"({"line": {"x0_m": 0, "y0_m": 0, "x1_m": 0.1, "y1_m": 0, "duration_s": 1e-300}})", "line.duration_s"},
      {R"({"lissajous": {"amplitude_x_m": 1e308, "amplitude_y_m": 0.01, "frequency_x": 1, "frequency_y": 2,
          "period_s": 8}})", "lissajous.amplitude_x_m"},
      {R"({"lissajous": {"amplitude_x_m": 0.01, "amplitude_y_m": 0.01, "frequency_x": 1, "frequency_y": 2,
          "phase_rad": 1e308, "period_s": 8}})", "lissajous.phase_rad"},
      {R"({"polyline": {"points": [{"x_m": 0, "y_m": 0}, {"x_m": -1e308, "y_m": 0}], "max_speed_m_s": 0.1,
          "max_acceleration_m_s2": 1}})", "polyline.points[1].x_m"},
      {R"({"polyline": {"points": [{"x_m": 0, "y_m": 0}, {"x_m": 0.1, "y_m": 0}], "max_speed_m_s": 1e-300,
          "max_acceleration_m_s2": 1}})", "polyline.max_speed_m_s"},
      {R"({"polyline": {"points": [{"x_m": 0, "y_m": 0}, {"x_m": 0.1, "y_m": 0}], "max_speed_m_s": 0.1,
          "max_acceleration_m_s2": 1, "max_jerk_m_s3": 1e308}})", "polyline.max_jerk_m_s3"},
      {R"({"spline": {"points": [{"x_m": 0, "y_m": 0}, {"x_m": 0.1, "y_m": "NaN"}, {"x_m": 0.2, "y_m": 0}],
          "feed": {"feed_m_s": 0.01, "max_normal_acceleration_m_s2": 1}}})", "spline.points[1].y_m"},
      {R"({"heart": {"scale_m": 1e308, "period_s": 10}})", "heart.scale_m"},
      {R"({"heart": {"scale_m": 0.0025, "center_y_m": 1e308, "period_s": 10}})", "heart.center_y_m"},
      {R"({"circle": {"radius_m": 0.01, "period_s": 8}, "halt": {"at_s": 1, "duration_s": 1e308}})",
       "halt.duration_s"},
  };
  for (const auto& c : cases) {
    const std::string error = error_of(spec_of(c.trajectory));
    EXPECT_EQ(error.rfind("trajectory." + c.field + ": expected ", 0), 0u) << c.field << ": " << error;
  }
}

TEST(ReferenceLimits, SpatialAndSingleAxisReferencesAreBoundedToo) {
  const std::string spatial = R"({"spatial_circle": {"center_x_m": 0.1, "center_y_m": 0.1, "center_z_m": 0.05,
      "radius_m": 0.05, "normal_x": 1, "normal_y": 1, "normal_z": 1, "start_x": 1, "start_y": 0, "start_z": 0,
      "period_s": 1.6, "revolutions": 1}})";
  const std::string law = "gtcf-sarc";
  EXPECT_EQ(error_of(spec_of(spatial, law)).find("trajectory."), std::string::npos) << error_of(spec_of(spatial, law));
  auto spec = spec_of(spatial, law);
  spec.mutable_trajectory()->mutable_spatial_circle()->set_center_z_m(1e308);
  EXPECT_EQ(error_of(spec).rfind("trajectory.spatial_circle.center_z_m: expected", 0), 0u) << error_of(spec);
  spec = spec_of(spatial, law);
  spec.mutable_trajectory()->mutable_spatial_circle()->set_normal_x(1e308);
  EXPECT_EQ(error_of(spec).rfind("trajectory.spatial_circle.normal_x: expected", 0), 0u) << error_of(spec);
  spec = spec_of(spatial, law);
  spec.mutable_trajectory()->mutable_spatial_circle()->set_period_s(1e-300);
  EXPECT_EQ(error_of(spec).rfind("trajectory.spatial_circle.period_s: expected", 0), 0u) << error_of(spec);

  const std::string sine = R"({"multi_sine": {"offset_m": 0, "terms": [{"amplitude_m": 0.08, "frequency_hz": 0.5}],
      "duration_s": 20, "period_s": 10}})";
  spec = spec_of(sine, "axis-diarc");
  spec.mutable_trajectory()->mutable_multi_sine()->set_offset_m(1e308);
  EXPECT_EQ(error_of(spec).rfind("trajectory.multi_sine.offset_m: expected", 0), 0u) << error_of(spec);
  spec = spec_of(sine, "axis-diarc");
  spec.mutable_trajectory()->mutable_multi_sine()->mutable_terms(0)->set_amplitude_m(1e308);
  EXPECT_EQ(error_of(spec).rfind("trajectory.multi_sine.terms[0].amplitude_m: expected", 0), 0u) << error_of(spec);
  spec = spec_of(sine, "axis-diarc");
  spec.mutable_trajectory()->mutable_multi_sine()->mutable_terms(0)->set_frequency_hz(1e308);
  EXPECT_EQ(error_of(spec).rfind("trajectory.multi_sine.terms[0].frequency_hz: expected a number in [0, 20] Hz", 0), 0u)
      << error_of(spec);
  spec = spec_of(sine, "axis-diarc");
  spec.mutable_trajectory()->mutable_multi_sine()->set_period_s(1e-300);
  EXPECT_EQ(error_of(spec).rfind("trajectory.multi_sine.period_s: expected", 0), 0u) << error_of(spec);
}

TEST(ReferenceLimits, TheStartingPointIsInTheWorkspace) {
  auto spec = circle();
  spec.mutable_initial_position()->set_x_m(1e308);
  EXPECT_EQ(error_of(spec), "initial_position.x: expected a number in [-10, 10] m, got 1e+308");
  spec.mutable_initial_position()->set_x_m(kNan);
  EXPECT_EQ(error_of(spec), "initial_position.x: expected a number in [-10, 10] m, got nan");
}

}  // namespace
}  // namespace netmc::job

namespace netmc::job {
namespace {

// What an iteration stores per cycle (an ILC's previous errors and commands) bounds its length.
TEST(RunLengthLimits, AnIterationOfMoreThan1e7CyclesIsRefused) {
  auto spec = parse_job_spec_json(R"({"trajectory": {"circle": {"radius_m": 0.01, "period_s": 8}},
                                      "controller": {"name": "adrc"}, "sample_period_s": 0.005})", "test");
  apply_defaults(spec);
  spec.set_duration_s(50000.0);  // 1e7 cycles of 5 ms
  EXPECT_EQ(error_of(spec), "");
  spec.set_duration_s(200000.0);
  EXPECT_EQ(error_of(spec),
            "duration: expected at most 1e7 cycles per iteration (run length / sample period), got 200000.000000 s / "
            "0.005000 s");
}

}  // namespace
}  // namespace netmc::job
