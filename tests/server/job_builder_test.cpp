// The control-plane edge: JSON specs through protobuf's mapping, defaults, and errors that name
// the field.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "server/job/controller_gains.hpp"
#include "server/job/job_builder.hpp"
#include "tests/server/job_build_error.hpp"

namespace netmc::job {
namespace {

// The built controller's own account of its gains.
std::string controller_of(const sim::ContourJob& job) { return job.make_controller()->describe(); }

const control::ReferenceTrajectory& trajectory_of(const sim::ContourJob& job) {
  return *std::get<std::shared_ptr<const control::ReferenceTrajectory>>(job.reference);
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
  // kcd unset: paper 001's 40.
  EXPECT_NE(controller_of(job).find("ilccc(kcp=30, kcd=40)"), std::string::npos) << controller_of(job);
  EXPECT_NEAR(job.downlink.delay->mean_s(), 0.00055, 1e-15);
}

// The contour-error limit: none unless asked in lockstep; a realtime job's default is a quarter
// of the reference's size (the 20 mm circle sampled every 5 ms: 5 mm); a given one is kept and
// checked.
TEST(JobBuilder, ContourErrorLimitDefaultsOnlyForRealtime) {
  auto spec = valid_spec();
  EXPECT_TRUE(std::isinf(build_contour_job(spec).contour_error_limit_m));
  spec.set_clock("realtime");
  const auto realtime = build_contour_job(spec);
  EXPECT_NEAR(realtime.reference_size_m(), 0.02, 1e-12);  // 1600 samples of 8 s hit 0 and pi
  EXPECT_NEAR(realtime.contour_error_limit_m, kRealtimeContourErrorLimitShare * 0.02, 1e-12);
  spec.set_contour_error_limit_m(0.5e-3);
  EXPECT_EQ(build_contour_job(spec).contour_error_limit_m, 0.5e-3);
  spec.set_contour_error_limit_m(0.0);
  EXPECT_NE(error_of(spec).find("contour_error_limit_m: expected a length in (0, 1000] m"), std::string::npos);
  spec.set_contour_error_limit_m(std::nan(""));
  EXPECT_NE(error_of(spec).find("contour_error_limit_m"), std::string::npos);
}

TEST(JobBuilder, ContourLibraryShapesFromJson) {
  const auto build = [](const std::string& trajectory) {
    auto spec = parse_job_spec_json(R"({"trajectory": )" + trajectory + "}", "test");
    apply_defaults(spec);
    return build_contour_job(spec);
  };
  const auto figure = build(R"({"lissajous": {"amplitude_x_m": 0.02, "amplitude_y_m": 0.015, "frequency_x": 3,
                                               "frequency_y": 2, "center_x_m": 0.05, "center_y_m": 0.05, "period_s": 20}})");
  EXPECT_DOUBLE_EQ(trajectory_of(figure).duration_s(), 20.0);
  EXPECT_NEAR(trajectory_of(figure).sample(0.0).position.y(), 0.05, 1e-15);
  const auto fed = build(R"({"lissajous": {"amplitude_x_m": 0.02, "amplitude_y_m": 0.015, "frequency_x": 3,
                                            "frequency_y": 2, "feed": {"feed_m_s": 0.01, "max_normal_acceleration_m_s2": 0.02}}})");
  EXPECT_LT(trajectory_of(fed).sample(0.0).velocity.norm(), 1e-15);  // from rest
  EXPECT_NE(trajectory_of(fed).describe().find("feed=10 mm/s"), std::string::npos);
  const auto square = build(R"({"polyline": {"points": [{"x_m": 0, "y_m": 0}, {"x_m": 0.02, "y_m": 0}, {"x_m": 0.02, "y_m": 0.01}],
                                             "max_speed_m_s": 0.01, "max_acceleration_m_s2": 0.05}})");
  EXPECT_NEAR(trajectory_of(square).duration_s(), (0.02 / 0.01 + 0.2) + (0.01 / 0.01 + 0.2), 1e-12);
  const auto spline = build(R"({"spline": {"points": [{"x_m": 0, "y_m": 0}, {"x_m": 0.03, "y_m": -0.005}, {"x_m": 0.05, "y_m": 0.01},
                                                       {"x_m": 0.02, "y_m": 0.02}, {"x_m": 0, "y_m": 0}],
                                            "feed": {"feed_m_s": 0.02, "max_normal_acceleration_m_s2": 0.05}}})");
  EXPECT_LT(trajectory_of(spline).sample(trajectory_of(spline).duration_s()).position.norm(), 1e-15);

  const auto error = [&](const std::string& trajectory) {
    auto spec = parse_job_spec_json(R"({"trajectory": )" + trajectory + "}", "test");
    apply_defaults(spec);
    return error_of(spec);
  };
  EXPECT_NE(error(R"({"polyline": {"points": [{"x_m": 0}], "max_speed_m_s": 0.01, "max_acceleration_m_s2": 0.05}})")
                .find("trajectory: polyline points: expected at least two points"),
            std::string::npos);
  EXPECT_NE(error(R"({"spline": {"points": [{"x_m": 0}, {"x_m": 0.01}]}})").find("trajectory.spline.feed.feed_m_s: expected"),
            std::string::npos);
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
  set_gain(*spec.mutable_controller(), "adrc", "kp", std::nan(""));
  EXPECT_NE(error_of(spec).find("controller.gains.adrc.kp: expected a finite number"), std::string::npos)
      << error_of(spec);

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
  // The gains by group, the y axis's own under axes.
  auto spec = parse_job_spec_json(R"({
    "trajectory": {"circle": {"radius_m": 0.04, "period_s": 0.4}},
    "controller": {"name": "adrc",
                   "gains": {"adrc": {"values": {"w0": 1500, "b0": 10, "kp": 9000},
                                      "axes": {"y": {"values": {"b0": 1.8}, "choices": {"observer": "zoh"}}}},
                             "gtcf_adrc": {"values": {"wc": 250, "wom": 400}, "choices": {"observer": "zoh"}}}}
  })", "test");
  apply_defaults(spec);
  const std::string adrc = controller_of(build_contour_job(spec));
  // The y axis takes the group's gains where it has none of its own.
  EXPECT_NE(adrc.find("adrc(r0=160, w0=1500, b0=10, kp=9000, kd=6, observer=euler) x "
                      "adrc(r0=160, w0=1500, b0=1.8, kp=9000, kd=6, observer=zoh)"),
            std::string::npos)
      << adrc;
  spec.mutable_controller()->set_name("gtcf-adrc");
  const std::string gtcf = controller_of(build_contour_job(spec));
  EXPECT_NE(gtcf.find("gtcf-adrc(wc=250, wm=100, woc=1500, wom=400, observer=zoh"), std::string::npos) << gtcf;

  set_gain_choice(*spec.mutable_controller(), "gtcf_adrc", "observer", "rk4");
  EXPECT_NE(error_of(spec).find("controller.gains.gtcf_adrc.observer: expected euler or zoh"), std::string::npos)
      << error_of(spec);
  set_gain_choice(*spec.mutable_controller(), "gtcf_adrc", "observer", "euler");
  set_gain(*spec.mutable_controller(), "gtcf_adrc", "wc", -1.0);
  EXPECT_NE(error_of(spec).find("controller.gains.gtcf_adrc.wc: expected a positive finite number"), std::string::npos)
      << error_of(spec);
}

// netmc 0.1's spec files named a message per family (adrc, adrc_y, ...), in snake_case or
// camelCase: they are read into the gains they stand for and build the same controller.
TEST(JobBuilder, LegacyTypedGainsReadAsTheGainsTheyStandFor) {
  const auto build = [](const std::string& controller) {
    auto spec = parse_job_spec_json(R"({"trajectory": {"circle": {"radius_m": 0.04, "period_s": 0.4}},
                                        "axes": ["a", "b"], "controller": )" + controller + "}",
                                    "test");
    apply_defaults(spec);
    return controller_of(build_contour_job(spec));
  };
  const std::string legacy = build(R"({"name": "adrc+ilccc",
      "adrc": {"w0": 1500, "observer_sees_sent_command": true}, "adrcY": {"b0": 1.8, "observer": "zoh"},
      "ilccc": {"kcp": 30, "qCutoffHz": 20, "lead_samples": 2}})");
  const std::string current = build(R"({"name": "adrc+ilccc", "gains": {
      "adrc": {"values": {"w0": 1500}, "choices": {"observer_input": "sent"},
               "axes": {"b": {"values": {"b0": 1.8}, "choices": {"observer": "zoh"}}}},
      "ilccc": {"values": {"kcp": 30, "q_cutoff_hz": 20, "lead_samples": 2}}}})");
  EXPECT_EQ(legacy, current);
  EXPECT_NE(legacy.find("b0=1.8, kp=0.08, kd=6, observer=zoh, observer input=sent"), std::string::npos) << legacy;
  EXPECT_NE(legacy.find("q=20 Hz, lead=2"), std::string::npos) << legacy;
  // A file with both forms is refused (the legacy field is unknown to the current spec).
  EXPECT_THROW(build(R"({"name": "adrc", "adrc": {"w0": 1500}, "gains": {}})"), std::invalid_argument);
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
  EXPECT_NE(trajectory_of(job).describe().find("heart"), std::string::npos);
  const std::string x = job.axes[0]->describe(), y = job.axes[1]->describe();
  // paper 002's 3 kg load: J' = 0.8e-3 + 3 * 0.005^2 = 0.875e-3 kg m^2 (netmc's assumption [A])
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
  // Unset: Table 1 (x: 24 kg, alpha 3), Table 2 (y: 50 Hz, 85 %), Table 3 (lpccc).
  const std::string c = controller_of(job);
  EXPECT_NE(c.find("ffpid(m=24 kg, f_bw=40 Hz, alpha=3, ff=0.9)"), std::string::npos) << c;
  EXPECT_NE(c.find("ffpid(m=32 kg, f_bw=50 Hz, alpha=2.5, ff=0.85)"), std::string::npos) << c;
  // eq. 13: (kd s^2 + kp s + ki) wn^2 / (s (s^2 + 2 z wn s + wn^2)), wn = 2 pi 120 Hz, z = 0.707, kp
  // 4e5 given, ki 1e8 and kd 3 from Table 3.
  EXPECT_NE(c.find("lpccc(C(s) = (1.70547e+06 s^2 + 2.27396e+11 s + 5.68489e+13) / (s^3 + 1066.13 s^2 + 568489 s))"),
            std::string::npos)
      << c;
  EXPECT_EQ(job.cycles(), 50001u);  // 2.5 s at 20 kHz: the circle's 2 s and 0.5 s at rest
  EXPECT_NE(trajectory_of(job).describe().find("ramp=0.2 s"), std::string::npos);
  EXPECT_EQ(trajectory_of(job).sample(2.2).velocity.norm(), 0.0);
  const std::string detail = job.make_controller()->describe();
  EXPECT_NE(detail.find("lpccc"), std::string::npos) << detail;
  EXPECT_NE(detail.find("m=32 kg"), std::string::npos) << detail;

  const auto sharp = parse_job_spec_json(R"({"trajectory": {"polyline": {
    "points": [{"x_m": 0, "y_m": 0}, {"x_m": 0.1, "y_m": 0}, {"x_m": 0.1, "y_m": 0.1}],
    "max_speed_m_s": 0.1, "max_acceleration_m_s2": 1, "max_jerk_m_s3": 10}}})", "test");
  auto sharp_spec = spec;
  *sharp_spec.mutable_trajectory() = sharp.trajectory();
  EXPECT_NEAR(trajectory_of(build_contour_job(sharp_spec)).duration_s(), 2.4, 1e-12);

  const auto error_with = [&](const std::string& controller) {
    auto bad = spec;
    *bad.mutable_controller() = parse_job_spec_json(R"({"controller": )" + controller + "}", "test").controller();
    return error_of(bad);
  };
  EXPECT_NE(error_with(R"({"name": "ffpid", "ffpid_x": {"mass_kg": -24}})")
                .find("controller.gains.ffpid.axes.x.mass_kg: expected a positive finite number"),
            std::string::npos);
  EXPECT_NE(error_with(R"({"name": "ffpid", "ffpid_y": {"alpha": 0}})").find("controller.gains.ffpid.axes.y.alpha"),
            std::string::npos);
  EXPECT_NE(error_with(R"({"name": "ffpid", "ffpid_y": {"low_pass_damping": -1}})")
                .find("controller.gains.ffpid.axes.y.low_pass_damping"),
            std::string::npos);
  EXPECT_NE(error_with(R"({"name": "ffpid+lpccc", "lpccc": {"low_pass_hz": 0}})").find("controller.gains.lpccc.low_pass_hz"),
            std::string::npos);
  // alpha f_bw = 3 x 5000 Hz is beyond the 10 kHz Nyquist frequency of the 20 kHz loop.
  const std::string nyquist = error_with(R"({"name": "ffpid", "ffpid_x": {"bandwidth_hz": 5000}})");
  EXPECT_NE(nyquist.find("controller: ffpid alpha * bandwidth_hz"), std::string::npos) << nyquist;
  EXPECT_NE(error_with(R"({"name": "ffpid+qft"})").find("unknown name 'ffpid+qft'"), std::string::npos);

  auto long_ramp = spec;
  long_ramp.mutable_trajectory()->mutable_circle()->set_ramp_s(1.5);
  EXPECT_NE(error_of(long_ramp).find("trajectory: circle ramp"), std::string::npos);
  auto corner_speed = sharp_spec;
  corner_speed.mutable_trajectory()->mutable_polyline()->set_corner_speed_m_s(0.05);
  EXPECT_NE(error_of(corner_speed).find("trajectory: polyline corner speed"), std::string::npos);
}

}  // namespace
}  // namespace netmc::job
