// The control-plane edge: JSON specs through protobuf's mapping, defaults, and errors that name
// the field.
#include <gtest/gtest.h>

#include <fstream>

#include "server/job/job_builder.hpp"

namespace netmc::job {
namespace {

std::string error_of(const netmc::v1::JobSpec& spec) {
  try {
    build_contour_job(spec);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

netmc::v1::JobSpec valid_spec() {
  auto spec = parse_job_spec_json(R"({
    "trajectory": {"circle": {"radius_m": 0.01, "center_x_m": 0.05, "center_y_m": 0.05, "period_s": 8}},
    "controller": {"name": "adrc+ilccc", "ilccc": {"kcp": 30}},
    "downlink": {"delay": {"uniform": {"min_s": 0.0003, "max_s": 0.0008}}},
    "iterations": 3
  })", "test");
  apply_defaults(spec);
  return spec;
}

TEST(JobBuilder, JsonSpecWithDefaults) {
  const auto spec = valid_spec();
  EXPECT_EQ(spec.plant(), "seed001");
  EXPECT_EQ(spec.sample_period_s(), 0.005);
  EXPECT_EQ(spec.seed(), 1u);
  const auto job = build_contour_job(spec);
  EXPECT_EQ(job.iterations, 3u);
  EXPECT_EQ(job.cycles(), 1601u);
  EXPECT_EQ(job.controller.ilccc.kcp, 30.0);
  EXPECT_EQ(job.controller.ilccc.kcd, 40.0);  // unset: paper 001
  EXPECT_NEAR(job.downlink.delay->mean_s(), 0.00055, 1e-15);
}

TEST(JobBuilder, ContourLibraryShapesFromJson) {
  const auto build = [](const std::string& trajectory) {
    auto spec = parse_job_spec_json(R"({"trajectory": )" + trajectory + "}", "test");
    apply_defaults(spec);
    return build_contour_job(spec);
  };
  const auto figure = build(R"({"lissajous": {"amplitude_x_m": 0.02, "amplitude_y_m": 0.015, "frequency_x": 3,
                                               "frequency_y": 2, "center_x_m": 0.05, "center_y_m": 0.05, "period_s": 20}})");
  EXPECT_DOUBLE_EQ(figure.trajectory->duration_s(), 20.0);
  EXPECT_NEAR(figure.trajectory->sample(0.0).position.y(), 0.05, 1e-15);
  const auto fed = build(R"({"lissajous": {"amplitude_x_m": 0.02, "amplitude_y_m": 0.015, "frequency_x": 3,
                                            "frequency_y": 2, "feed": {"feed_m_s": 0.01, "max_normal_acceleration_m_s2": 0.02}}})");
  EXPECT_LT(fed.trajectory->sample(0.0).velocity.norm(), 1e-15);  // from rest
  EXPECT_NE(fed.trajectory->describe().find("feed=10 mm/s"), std::string::npos);
  const auto square = build(R"({"polyline": {"points": [{"x_m": 0, "y_m": 0}, {"x_m": 0.02, "y_m": 0}, {"x_m": 0.02, "y_m": 0.01}],
                                             "max_speed_m_s": 0.01, "max_acceleration_m_s2": 0.05}})");
  EXPECT_NEAR(square.trajectory->duration_s(), (0.02 / 0.01 + 0.2) + (0.01 / 0.01 + 0.2), 1e-12);
  const auto spline = build(R"({"spline": {"points": [{"x_m": 0, "y_m": 0}, {"x_m": 0.03, "y_m": -0.005}, {"x_m": 0.05, "y_m": 0.01},
                                                       {"x_m": 0.02, "y_m": 0.02}, {"x_m": 0, "y_m": 0}],
                                            "feed": {"feed_m_s": 0.02, "max_normal_acceleration_m_s2": 0.05}}})");
  EXPECT_LT(spline.trajectory->sample(spline.trajectory->duration_s()).position.norm(), 1e-15);

  const auto error = [&](const std::string& trajectory) {
    auto spec = parse_job_spec_json(R"({"trajectory": )" + trajectory + "}", "test");
    apply_defaults(spec);
    return error_of(spec);
  };
  EXPECT_NE(error(R"({"polyline": {"points": [{"x_m": 0}], "max_speed_m_s": 0.01, "max_acceleration_m_s2": 0.05}})")
                .find("trajectory: polyline points: expected at least two points"),
            std::string::npos);
  EXPECT_NE(error(R"({"spline": {"points": [{"x_m": 0}, {"x_m": 0.01}]}})").find("trajectory: feed"), std::string::npos);
  EXPECT_NE(error(R"({"lissajous": {"amplitude_x_m": 0.02, "amplitude_y_m": 0.015, "frequency_x": 1, "frequency_y": 1, "period_s": 4}})")
                .find("retraces itself"),
            std::string::npos);
}

TEST(JobBuilder, ErrorsNameTheField) {
  auto spec = valid_spec();
  spec.mutable_controller()->set_name("adrc+fuzzy");
  EXPECT_NE(error_of(spec).find("controller"), std::string::npos);

  spec = valid_spec();
  spec.set_sample_period_s(-0.005);
  EXPECT_NE(error_of(spec).find("sample_period"), std::string::npos);

  spec = valid_spec();
  spec.mutable_controller()->mutable_adrc()->set_kp(std::nan(""));
  EXPECT_NE(error_of(spec).find("adrc kp"), std::string::npos);

  spec = valid_spec();
  spec.mutable_downlink()->mutable_delay()->mutable_uniform()->set_min_s(0.002);
  EXPECT_NE(error_of(spec).find("downlink.delay"), std::string::npos);

  spec = valid_spec();
  spec.mutable_downlink()->mutable_delay()->mutable_trace()->set_path("/nonexistent/trace.csv");
  const std::string trace_error = error_of(spec);
  EXPECT_NE(trace_error.find("downlink.delay"), std::string::npos);
  EXPECT_NE(trace_error.find("/nonexistent/trace.csv"), std::string::npos);

  spec = valid_spec();
  spec.set_plant("steam-engine");
  EXPECT_NE(error_of(spec).find("plant"), std::string::npos);

  spec = valid_spec();
  spec.mutable_trajectory()->clear_circle();
  EXPECT_NE(error_of(spec).find("trajectory"), std::string::npos);

  EXPECT_THROW(parse_job_spec_json(R"({"iterations": "many"})", "spec.json"), std::invalid_argument);
  EXPECT_THROW(parse_job_spec_json(R"({"no_such_field": 1})", "spec.json"), std::invalid_argument);
}

TEST(JobBuilder, JsonOutputUsesProtoFieldNames) {
  sim::IterationMetrics m;
  m.iteration = 2;
  m.e_max_m = 1.5e-5;
  const std::string json = to_json(to_proto(m));
  EXPECT_NE(json.find("\"e_max_m\": 1.5e-05"), std::string::npos) << json;
  EXPECT_NE(json.find("\"iteration\": 2"), std::string::npos) << json;
}

}  // namespace
}  // namespace netmc::job
