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

TEST(JobBuilder, PerAxisAdrcAndTaskSpaceAdrcGains) {
  auto spec = parse_job_spec_json(R"({
    "trajectory": {"circle": {"radius_m": 0.04, "period_s": 0.4}},
    "controller": {"name": "adrc",
                   "adrc": {"w0": 1500, "b0": 10, "kp": 9000},
                   "adrc_y": {"b0": 1.8, "observer": "zoh"},
                   "gtcf_adrc": {"wc": 250, "wom": 400, "observer": "zoh"}}
  })", "test");
  apply_defaults(spec);
  const auto job = build_contour_job(spec);
  ASSERT_TRUE(job.controller.adrc_y.has_value());
  // The y axis takes the x axis's gains where its own are unset.
  EXPECT_EQ(job.controller.adrc_y->input_gain, 1.8);
  EXPECT_EQ(job.controller.adrc_y->observer_bandwidth, 1500.0);
  EXPECT_EQ(job.controller.adrc_y->kp, 9000.0);
  EXPECT_EQ(job.controller.adrc_y->observer_discretization, control::Discretization::zero_order_hold);
  EXPECT_EQ(job.controller.adrc.observer_discretization, control::Discretization::forward_euler);
  const auto& g = job.controller.gtcf_adrc;
  EXPECT_EQ(g.loop_bandwidth, Eigen::Vector2d(250.0, control::GtcfAdrcGains{}.loop_bandwidth[1]));
  EXPECT_EQ(g.observer_bandwidth, Eigen::Vector2d(control::GtcfAdrcGains{}.observer_bandwidth[0], 400.0));
  EXPECT_EQ(g.discretization, control::Discretization::zero_order_hold);

  spec.mutable_controller()->mutable_gtcf_adrc()->set_observer("rk4");
  EXPECT_NE(error_of(spec).find("controller.gtcf_adrc.observer"), std::string::npos);
  spec.mutable_controller()->mutable_gtcf_adrc()->set_observer("");
  spec.mutable_controller()->set_name("gtcf-adrc");
  spec.mutable_controller()->mutable_gtcf_adrc()->set_wc(-1.0);
  EXPECT_NE(error_of(spec).find("gtcf-adrc loop bandwidth"), std::string::npos);
}

TEST(JobBuilder, TaskSpaceFilterAndInitialPosition) {
  auto spec = parse_job_spec_json(R"({
    "trajectory": {"circle": {"radius_m": 0.04, "center_y_m": 0.05, "period_s": 0.4, "clockwise": true}},
    "plant": "linmotor",
    "controller": {"name": "gtcf-darc", "task_space": {"initialization_filter": true, "filter_wm": 2}},
    "initial_position": {"x_m": 0.0, "y_m": 0.0}
  })", "test");
  apply_defaults(spec);
  const auto job = build_contour_job(spec);
  EXPECT_TRUE(job.controller.initialization_filter.enabled);
  EXPECT_EQ(job.controller.initialization_filter.contour_bandwidth, 8.0);  // unset: thesis
  EXPECT_EQ(job.controller.initialization_filter.tangential_bandwidth, 2.0);
  ASSERT_TRUE(job.initial_position.has_value());
  EXPECT_EQ(job.start_position(), Eigen::Vector2d(0.0, 0.0));
  // Unset, the axes start on the trajectory.
  spec.clear_initial_position();
  EXPECT_EQ(build_contour_job(spec).start_position(), Eigen::Vector2d(0.04, 0.05));
  // The filter lives in the global task frame only.
  spec.mutable_controller()->set_name("ltcf-sarc");
  EXPECT_NE(error_of(spec).find("controller: initialization filter"), std::string::npos);
}

TEST(JobBuilder, JsonOutputUsesProtoFieldNames) {
  sim::IterationMetrics m;
  m.iteration = 2;
  m.e_max_m = 1.5e-5;
  const std::string json = to_json(to_proto(m));
  EXPECT_NE(json.find("\"e_max_m\": 1.5e-05"), std::string::npos) << json;
  EXPECT_NE(json.find("\"iteration\": 2"), std::string::npos) << json;
}

TEST(JobBuilder, SteadyMetricsAreAbsentWithoutAnEvaluationWindowNeverZero) {
  sim::IterationMetrics m;
  m.command_rms_steady = {0.0, 0.0};
  const auto without = to_proto(m);  // no sample in the window
  EXPECT_FALSE(without.has_e_rms_steady_m());
  EXPECT_FALSE(without.has_e_max_steady_m());
  EXPECT_EQ(without.command_rms_steady_size(), 0);
  EXPECT_EQ(to_json(without).find("steady_m"), std::string::npos);
  m.steady_samples = 400;
  m.e_rms_steady_m = 0.0;  // a perfect steady state is a measured 0, and it is shown
  m.e_max_steady_m = 2e-6;
  const auto with = to_proto(m);
  EXPECT_TRUE(with.has_e_rms_steady_m());
  EXPECT_EQ(with.e_max_steady_m(), 2e-6);
  EXPECT_EQ(with.command_rms_steady_size(), 2);
  EXPECT_NE(to_json(with).find("\"e_rms_steady_m\": 0"), std::string::npos);
}

}  // namespace
}  // namespace netmc::job

namespace netmc::job {
namespace {

TEST(JobBuilder, AxisNamesDefaultToXYAndAreChecked) {
  auto spec = valid_spec();
  EXPECT_EQ(axis_names(spec), (std::vector<std::string>{"x", "y"}));
  spec.add_axes("stage1.x");
  spec.add_axes("stage1.y");
  EXPECT_EQ(axis_names(spec), (std::vector<std::string>{"stage1.x", "stage1.y"}));
  EXPECT_EQ(error_of(spec), "");
  for (const auto& bad : std::vector<std::vector<std::string>>{
           {"x"}, {"x", "x"}, {"x", "y z"}, {"x", "it's"}, {"x", std::string(65, 'a')}, {"x", ""}}) {
    spec.clear_axes();
    for (const auto& name : bad) spec.add_axes(name);
    EXPECT_EQ(error_of(spec).rfind("axes: ", 0), 0u) << error_of(spec);
  }
}

}  // namespace
}  // namespace netmc::job

namespace netmc::job {
namespace {

TEST(JobBuilder, PlantOverridesAndDisturbancesPerAxis) {
  auto spec = parse_job_spec_json(R"({
    "trajectory": {"heart": {"scale_m": 0.0025, "center_x_m": 0.075, "center_y_m": 0.075, "period_s": 10}},
    "plant": "ballscrew",
    "controller": {"name": "pid", "pid": {"kp": 100}, "pid_y": {"kp": 50}, "estimator": "steffensen"},
    "sample_period_s": 0.001,
    "plant_axes": [
      {"axis": "y", "parameters": [{"key": "load_kg", "value": 3}],
       "disturbance": {"step": {"amplitude": 0.8, "on_s": 2.2, "off_s": 5.2},
                       "sine": {"amplitude": 0.1, "frequency_hz": 2}}}
    ]
  })", "test");
  apply_defaults(spec);
  const sim::ContourJob job = build_contour_job(spec);
  EXPECT_NE(job.trajectory->describe().find("heart"), std::string::npos);
  const std::string x = job.axes[0]->describe(), y = job.axes[1]->describe();
  // paper 002's 3 kg load: J' = 0.8e-3 + 3 * 0.005^2 = 0.875e-3 kg m^2 (digest 3.7 [A])
  EXPECT_NE(y.find("0.000875"), std::string::npos) << y;
  EXPECT_EQ(x.find("0.000875"), std::string::npos) << x;
  EXPECT_NE(y.find("step 0.8 from 2.2 s to 5.2 s"), std::string::npos) << y;
  EXPECT_NE(x.find("d=none"), std::string::npos) << x;
}

TEST(JobBuilder, PlantOverrideErrorsNameTheField) {
  auto with = [](const std::string& plant_axes) {
    auto spec = valid_spec();
    spec.set_plant("ballscrew");
    auto parsed = parse_job_spec_json("{\"plant_axes\": " + plant_axes + "}", "test");
    *spec.mutable_plant_axes() = parsed.plant_axes();
    return error_of(spec);
  };
  EXPECT_NE(with(R"([{"axis": "w"}])").find("plant_axes[0].axis: expected an axis of the job"), std::string::npos);
  EXPECT_NE(with(R"([{"axis": "x"}, {"axis": "x"}])").find("plant_axes[1].axis"), std::string::npos);
  const std::string unknown = with(R"([{"axis": "x", "parameters": [{"key": "mass", "value": 1}]}])");
  EXPECT_NE(unknown.find("ballscrew has no parameter 'mass' (expected one of: inertia_kg_m2"), std::string::npos)
      << unknown;
  EXPECT_NE(with(R"([{"axis": "x", "parameters": [{"key": "load_kg", "value": -1}]}])").find("load_kg must be >= 0"),
            std::string::npos);
  EXPECT_NE(with(R"([{"axis": "x", "disturbance": {"step": {"amplitude": 1, "on_s": 3, "off_s": 2}}}])")
                .find("step_off_s"),
            std::string::npos);
  EXPECT_NE(with(R"([{"axis": "x", "disturbance": {"noise": {"stddev": 1}}}])").find("noise.bandwidth_hz"),
            std::string::npos);
}

// Paper 004: the per-axis loops (ffpid_x, ffpid_y), the PID-type cross-coupling (lpccc), the
// circle's ramp and the polyline's jerk limit; unset gains take Tables 1-3.
TEST(JobBuilder, Paper004GainsAndMotions) {
  auto spec = parse_job_spec_json(R"({
    "trajectory": {"circle": {"radius_m": 0.0636619772, "period_s": 2, "ramp_s": 0.2}},
    "plant": "stage004",
    "controller": {"name": "ffpid+lpccc", "estimator": "tangent",
                   "ffpid_x": {"bandwidth_hz": 40, "feedforward_fraction": 0.9},
                   "ffpid_y": {"mass_kg": 32, "alpha": 2.5, "low_pass_damping": 0.5},
                   "lpccc": {"kp": 4e5, "low_pass_hz": 120}},
    "sample_period_s": 5e-5,
    "duration_s": 2.5
  })", "test");
  apply_defaults(spec);
  const sim::ContourJob job = build_contour_job(spec);
  const auto& c = job.controller;
  EXPECT_EQ(c.ffpid_x.mass_kg, 24.0);  // Table 1
  EXPECT_EQ(c.ffpid_x.bandwidth_hz, 40.0);
  EXPECT_EQ(c.ffpid_x.alpha, 3.0);
  EXPECT_EQ(c.ffpid_x.low_pass_damping, 0.7);
  EXPECT_EQ(c.ffpid_x.feedforward_fraction, 0.9);
  EXPECT_EQ(c.ffpid_y.mass_kg, 32.0);
  EXPECT_EQ(c.ffpid_y.bandwidth_hz, 50.0);  // Table 2
  EXPECT_EQ(c.ffpid_y.alpha, 2.5);
  EXPECT_EQ(c.ffpid_y.low_pass_damping, 0.5);
  EXPECT_EQ(c.ffpid_y.feedforward_fraction, 0.85);
  EXPECT_EQ(c.lpccc.kp, 4e5);
  EXPECT_EQ(c.lpccc.ki, 1e8);  // Table 3
  EXPECT_EQ(c.lpccc.kd, 3.0);
  EXPECT_EQ(c.lpccc.low_pass_hz, 120.0);
  EXPECT_EQ(c.lpccc.low_pass_damping, 0.707);
  EXPECT_EQ(job.cycles(), 50001u);  // 2.5 s at 20 kHz: the circle's 2 s and 0.5 s at rest
  EXPECT_NE(job.trajectory->describe().find("ramp=0.2 s"), std::string::npos);
  EXPECT_EQ(job.trajectory->sample(2.2).velocity.norm(), 0.0);
  const std::string detail = job.make_controller()->describe();
  EXPECT_NE(detail.find("lpccc"), std::string::npos) << detail;
  EXPECT_NE(detail.find("m=32 kg"), std::string::npos) << detail;

  const auto sharp = parse_job_spec_json(R"({"trajectory": {"polyline": {
    "points": [{"x_m": 0, "y_m": 0}, {"x_m": 0.1, "y_m": 0}, {"x_m": 0.1, "y_m": 0.1}],
    "max_speed_m_s": 0.1, "max_acceleration_m_s2": 1, "max_jerk_m_s3": 10}}})", "test");
  auto sharp_spec = spec;
  *sharp_spec.mutable_trajectory() = sharp.trajectory();
  EXPECT_NEAR(build_contour_job(sharp_spec).trajectory->duration_s(), 2.4, 1e-12);

  const auto error_with = [&](const std::string& controller) {
    auto bad = spec;
    *bad.mutable_controller() = parse_job_spec_json(R"({"controller": )" + controller + "}", "test").controller();
    return error_of(bad);
  };
  EXPECT_NE(error_with(R"({"name": "ffpid", "ffpid_x": {"mass_kg": -24}})").find("controller.ffpid_x.mass_kg: expected a positive"),
            std::string::npos);
  EXPECT_NE(error_with(R"({"name": "ffpid", "ffpid_y": {"alpha": 0}})").find("controller.ffpid_y.alpha"), std::string::npos);
  EXPECT_NE(error_with(R"({"name": "ffpid", "ffpid_y": {"low_pass_damping": -1}})").find("controller.ffpid_y.low_pass_damping"),
            std::string::npos);
  EXPECT_NE(error_with(R"({"name": "ffpid+lpccc", "lpccc": {"low_pass_hz": 0}})").find("controller.lpccc.low_pass_hz"),
            std::string::npos);
  // alpha f_bw = 3 x 5000 Hz is beyond the 10 kHz Nyquist frequency of the 20 kHz loop.
  const std::string nyquist = error_with(R"({"name": "ffpid", "ffpid_x": {"bandwidth_hz": 5000}})");
  EXPECT_NE(nyquist.find("controller: ffpid alpha * bandwidth_hz"), std::string::npos) << nyquist;
  EXPECT_NE(error_with(R"({"name": "ffpid+qft"})").find("ffpid+qftccc"), std::string::npos);

  auto long_ramp = spec;
  long_ramp.mutable_trajectory()->mutable_circle()->set_ramp_s(1.5);
  EXPECT_NE(error_of(long_ramp).find("trajectory: circle ramp"), std::string::npos);
  auto corner_speed = sharp_spec;
  corner_speed.mutable_trajectory()->mutable_polyline()->set_corner_speed_m_s(0.05);
  EXPECT_NE(error_of(corner_speed).find("trajectory: polyline corner speed"), std::string::npos);
}

}  // namespace
}  // namespace netmc::job
