// JSON spec files: every mistake is reported at its field path, with what was expected and
// what was found; everything protobuf itself writes for a JobSpec is accepted.
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include "client/study_plan.hpp"
#include "client/spec_validation.hpp"
#include "server/job/controller_gains.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::cli {
namespace {

std::string error_of(const std::string& json) {
  try {
    validate_job_spec_json(json, "spec.json");
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(SpecValidation, ErrorsPointAtTheField) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {R"({"controller": {"gains": {"adrc": {"values": {"w0": "fast"}}}}})",
       "spec.json: controller.gains.adrc.values.w0: expected a number, got the text \"fast\""},
      {R"({"controller": {"gains": {"adrc": {"lists": {"lower": [1, 2]}}}}})",
       "spec.json: controller.gains.adrc.lists.lower: expected an object {...}, got a list"},
      {R"({"iterations": "many"})",
       "spec.json: iterations: expected a non-negative whole number, got the text \"many\""},
      {R"({"iterations": 2.5})", "spec.json: iterations: expected a non-negative whole number, got 2.5"},
      {R"({"iterations": -1})", "spec.json: iterations: expected a non-negative whole number, got -1"},
      {R"({"seed": "12x"})", "spec.json: seed: expected a non-negative whole number"},
      {R"({"downlink": {"loss": {"bernoulli": {"p": 1.5}}}})",
       "spec.json: downlink.loss.bernoulli.p: expected a number from 0 to 1, got 1.5"},
      {R"({"uplink": {"delay": {"uniform": {"min_s": -0.001, "max_s": 0.002}}}})",
       "spec.json: uplink.delay.uniform.min_s: expected a non-negative number, got -0.001"},
      {R"({"trajectory": {"circle": {"radius_m": 0.01}, "line": {"x1_m": 1}}})",
       "spec.json: trajectory: give only one of: circle, ellipse, line"},
      {R"({"trajectory": {"line": {"duration_s": 0}}})",
       "spec.json: trajectory.line.duration_s: expected a positive number, got 0"},
      {R"({"controler": {"name": "adrc"}})", "spec.json: controler: unknown field (expected one of: name, "},
      // netmc 0.1's typed gains are checked as the gains they stand for.
      {R"({"controller": {"ilccc": {"kcp": "40"}}})",
       "spec.json: controller.gains.ilccc.values.kcp: expected a number, got the text \"40\""},
      {R"({"controller": {"name": 7}})", "spec.json: controller.name: expected a text in quotes, got 7"},
      {R"({"controller": {"adrc": {"observer_sees_sent_command": "yes"}}})",
       "spec.json: controller.gains.adrc.values.observer_sees_sent_command: expected a number"},
      {R"({"downlink": {"delay": {"trace": {"delays_s": [0.001, -2]}}}})",
       "spec.json: downlink.delay.trace.delays_s[1]: expected a non-negative number, got -2"},
      {R"({"downlink": {"delay": {"trace": {"delays_s": 0.001}}}})",
       "spec.json: downlink.delay.trace.delays_s: expected a list [...], got 0.001"},
      {R"({"trajectory": [1, 2]})", "spec.json: trajectory: expected an object {...}, got a list"},
      {R"([])", "spec.json: expected an object {...}, got a list"},
      {"{\n  \"iterations\": 3,\n  \"seed\": }", "spec.json:3:11: not valid JSON"},
  };
  for (const auto& [json, expected] : cases) {
    EXPECT_EQ(error_of(json).rfind(expected, 0), 0u) << json << "\n" << error_of(json);
  }
}

TEST(SpecValidation, AcceptsWhatProtobufWritesAndItsCamelCaseNames) {
  auto job = seed001_job("adrc+ilccc");
  job::set_gain(*job.mutable_controller(), "adrc", "w0", 120);
  job::set_gain(*job.mutable_controller(), "ilccc", "q_cutoff_hz", 20);
  job.mutable_uplink()->mutable_loss()->mutable_gilbert_elliott()->set_p_good_to_bad(0.01);
  job::apply_defaults(job);
  const std::string json = job::to_json(job);  // every field, defaults included
  EXPECT_EQ(error_of(json), "") << json;
  const auto parsed = parse_job_spec_file_text(json, "spec.json");
  EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(parsed, job)) << json;

  EXPECT_EQ(error_of(R"({"samplePeriodS": 0.005, "controller": {"gains": {"ilccc": {"values": {"q_cutoff_hz": 20}}}}})"), "");
  // netmc 0.1's typed gains, camelCase too, are read as the gains they stand for.
  EXPECT_EQ(error_of(R"({"samplePeriodS": 0.005, "controller": {"ilccc": {"qCutoffHz": 20}}})"), "");
  EXPECT_EQ(parse_job_spec_file_text(R"({"controller": {"ilccc": {"qCutoffHz": 20}, "adrcY": {"w0": 90}}})", "spec.json")
                .controller()
                .gains()
                .at("adrc")
                .axes()
                .at("y")
                .values()
                .at("w0"),
            90.0);
  EXPECT_EQ(error_of(R"({"trajectory": null, "seed": "42", "iterations": 3.0})"), "");
}

// Every preset's jobs as protobuf writes them pass the checks: signed fields (a single-axis
// reference's phases, a dead zone's left break point and theta, a symmetric dead zone's plant
// parameters) are not refused as negative.
TEST(SpecValidation, AcceptsEveryPresetsJobsAndSignedFields) {
  for (const auto& name : preset_names()) {
    for (auto job : make_preset(name).jobs) {
      job::apply_defaults(job);
      EXPECT_EQ(error_of(job::to_json(job)), "") << name << ": " << job.name();
    }
  }
  EXPECT_EQ(error_of(R"({"plant_axes": [{"axis": "y", "parameters": [{"key": "dead_zone_left_v", "value": -0.3}],
                         "disturbance": {"step": {"amplitude": -0.8, "on_s": 2.2}, "constant": -0.1,
                                         "sine": {"amplitude": -0.2, "frequency_hz": 2}}}],
                         "controller": {"axis_diarc": {"lower": [1, 0.3, 5, 1.5, 5, -3]},
                                        "dead_zone_inverse": [{"axis": "x", "dead_zone": {"left_break_v": -0.25}}]}})"),
            "");
  EXPECT_EQ(error_of(R"({"plant_axes": [{"axis": "y", "disturbance": {"sine": {"frequency_hz": -2}}}]})"),
            "spec.json: plant_axes[0].disturbance.sine.frequency_hz: expected a non-negative number, got -2");
}

}  // namespace
}  // namespace netmc::cli
