// The controller registry: every family's defaults make a working controller on the plants they
// are tuned for, names and gains are checked against the families' own descriptors, per-axis
// gains go by axis name, netmc 0.1's typed gains still read, and the docs' table is the
// registry's.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "server/job/presets/presets.hpp"
#include "server/job/controller_registry.hpp"
#include "server/job/job_builder.hpp"
#include "tests/server/job_build_error.hpp"
#include "server/sim/contour_job_runner.hpp"

namespace netmc::job {
namespace {

// A job of the study that made each plant's numbers (its trajectory, sample period, sensor),
// run briefly, with no gains of the preset's.
netmc::v1::JobSpec plant_job(const std::string& plant, bool single_axis) {
  std::string preset = "seed001";
  if (plant == "linmotor" || plant == "linmotor-flex") preset = "thesis-ellipse";
  if (plant == "ballscrew") preset = "seed002";
  if (plant == "stage004") preset = "seed004";
  if (plant == "hiwin" || single_axis) preset = "thesis-dead-zone";
  netmc::v1::JobSpec spec = presets::make_preset(preset).jobs.front();
  spec.set_plant(single_axis && plant != "hiwin" ? spec.plant() : plant);
  spec.mutable_controller()->clear_gains();
  spec.mutable_controller()->clear_dead_zone_inverse();
  spec.set_iterations(1);
  // The thesis's ellipse twice round, not 28 times: the laws settle within the first.
  if (spec.trajectory().has_ellipse()) spec.mutable_trajectory()->mutable_ellipse()->set_revolutions(2.0);
  apply_defaults(spec);
  return spec;
}

// What each compensator composes with on its plant.
std::string with_compensator(const std::string& plant, const std::string& compensator) {
  return (plant == "stage004" ? "ffpid+" : "adrc+") + compensator;
}

TEST(ControllerRegistry, EveryFamilysDefaultsMakeAWorkingControllerOnTheirPlants) {
  std::size_t runs = 0;
  for (const auto& family : ControllerRegistry::global().families()) {
    const bool single_axis = family.role == ControllerRole::tracking;
    if (family.plants.empty()) {
      // No working defaults on any plant: refused without the keys it needs, naming the flag.
      ASSERT_FALSE(family.required_gains.empty()) << family.names.front();
      auto spec = plant_job("ballscrew", false);
      spec.mutable_controller()->set_name(family.names.front());
      const std::string& group = family.gain_groups.front();
      EXPECT_NE(error_of(spec).find(ControllerRegistry::global().gain_group(group)->flag + " " +
                                    family.required_gains.front() + "="),
                std::string::npos)
          << error_of(spec);
      set_gain_choice(*spec.mutable_controller(), group, family.required_gains.front(), "full");
      EXPECT_EQ(error_of(spec), "");
      ++runs;
      continue;
    }
    for (const auto& plant : family.plants) {
      for (const auto& name : family.names) {
        auto spec = plant_job(plant, single_axis);
        spec.mutable_controller()->set_name(family.role == ControllerRole::compensator ? with_compensator(plant, name)
                                                                                        : name);
        const auto job = build_contour_job(spec);
        const auto m = sim::ContourJobRunner(job).run_iteration().metrics;
        ++runs;
        const std::string what = spec.controller().name() + " on " + plant;
        EXPECT_FALSE(m.diverged) << what;
        EXPECT_FALSE(m.did_not_follow) << what;
        // Working: the contour (or, on one axis, the tracking) error stays within a millimetre on
        // references of 10-200 mm (the studies' own figures are micrometres to tens of them).
        EXPECT_LT(m.e_max_m, 1e-3) << what;
        EXPECT_GT(m.e_max_m, 0.0) << what;  // a result, not an axis standing on the contour
      }
    }
  }
  EXPECT_GE(runs, 27u);  // the 27 built-in controller names and their plants
}

TEST(ControllerRegistry, PidTracksPaper001sCircleWithItsDefaults) {
  // Paper 001's circle (r = 10 mm), no gains given: a triple pole at 60 rad/s on the X axis.
  auto spec = plant_job("seed001", false);
  spec.mutable_controller()->set_name("pid");
  const auto m = sim::ContourJobRunner(build_contour_job(spec)).run_iteration().metrics;
  EXPECT_FALSE(m.did_not_follow);
  EXPECT_LT(m.e_max_m, 20e-6);  // measured 5.4 um
  // Zero gains: the axes stand still on the circle, e_max ~ 0, and the run is flagged.
  set_gain(*spec.mutable_controller(), "pid", "kp", 0.0);
  set_gain(*spec.mutable_controller(), "pid", "ki", 0.0);
  set_gain(*spec.mutable_controller(), "pid", "kd", 0.0);
  const auto still = sim::ContourJobRunner(build_contour_job(spec)).run_iteration().metrics;
  EXPECT_LT(still.e_max_m, 1e-6);
  EXPECT_TRUE(still.did_not_follow);
  EXPECT_NEAR(*std::max_element(still.tracking_max_m.begin(), still.tracking_max_m.end()), 0.02, 1e-9);
}

TEST(ControllerRegistry, NamesAreResolvedByRole) {
  const auto error = [](const std::string& name, bool single_axis = false) {
    auto spec = plant_job(single_axis ? "hiwin" : "seed001", single_axis);
    spec.mutable_controller()->set_name(name);
    return error_of(spec);
  };
  for (const auto& name : ControllerRegistry::global().families().front().names) EXPECT_EQ(error(name), "") << name;
  EXPECT_EQ(error("pid+ilccc"), "");
  EXPECT_EQ(error("adrc+pidccc"), "");
  for (const char* bad : {"adrc+fuzzy", "ilccc", "pidccc+adrc", "gtcf-sarc+ilccc", "adrc+ffpid", "fuzzy", ""}) {
    EXPECT_EQ(error(bad).rfind("controller: unknown name '" + std::string(bad) + "' (expected AXIS[+COMPENSATOR]", 0),
              0u)
        << bad << ": " << error(bad);
  }
  EXPECT_EQ(error("axis-avsc"), "controller: axis-avsc is a single-axis law: it runs --trajectory multi-sine");
  EXPECT_EQ(error("adrc", true), "controller: a single-axis job runs a single-axis law, got 'adrc'");
  // The help names every name once.
  const std::string help = ControllerRegistry::global().names_help();
  for (const auto& family : ControllerRegistry::global().families()) {
    for (const auto& name : family.names) EXPECT_NE(help.find(name), std::string::npos) << name;
  }
}

TEST(ControllerRegistry, GainsAreCheckedAgainstTheFamiliesKeys) {
  const auto error = [](const std::string& gains_json) {
    auto spec = plant_job("seed001", false);
    *spec.mutable_controller() =
        parse_job_spec_json(R"({"controller": {"name": "adrc+ilccc", "gains": )" + gains_json + "}}", "test").controller();
    return error_of(spec);
  };
  EXPECT_EQ(error(R"({"adrc": {"values": {"w0": 120}}, "ilccc": {"values": {"kcp": 30}}})"), "");
  const std::vector<std::pair<std::string, std::string>> cases{
      {R"({"adrcc": {}})", "controller.gains.adrcc: no such gains group (expected one of: adrc, pid, "},
      {R"({"adrc": {"values": {"w1": 1}}})", "controller.gains.adrc.w1: unknown key (expected one of: r0, w0, b0, kp, kd, "},
      {R"({"adrc": {"values": {"w0": -1}}})", "controller.gains.adrc.w0: expected a positive finite number, got -1"},
      {R"({"adrc": {"values": {"observer": 1}}})", "controller.gains.adrc.observer: is not a number"},
      {R"({"adrc": {"choices": {"observer": "rk4"}}})", "controller.gains.adrc.observer: expected euler or zoh, got 'rk4'"},
      {R"({"ilccc": {"values": {"lead_samples": 1.5}}})", "controller.gains.ilccc.lead_samples: expected a whole number"},
      {R"({"ilccc": {"axes": {"y": {"values": {"kcp": 1}}}}})", "controller.gains.ilccc.axes: the group takes no per-axis values"},
      {R"({"adrc": {"axes": {"w": {"values": {"w0": 1}}}}})",
       "controller.gains.adrc.axes.w: not an axis of the job (expected one of: x, y)"},
      {R"({"axis_diarc": {"lists": {"lower": {"values": [1, 2]}}}})",
       "controller.gains.axis_diarc.lower: expected 6 numbers, got 2"},
  };
  for (const auto& [gains, expected] : cases) {
    EXPECT_EQ(error(gains).rfind(expected, 0), 0u) << gains << "\n" << error(gains);
  }
  // Not a number at all (NaN cannot be written in JSON; a spec from the network can carry it).
  auto spec = plant_job("seed001", false);
  set_gain(*spec.mutable_controller(), "adrc", "kp", std::nan(""));
  EXPECT_EQ(error_of(spec).rfind("controller.gains.adrc.kp: expected a finite number, got nan", 0), 0u) << error_of(spec);
}

// Per-axis gains go by the job's axis names, for any names; renaming the axes moves them along.
TEST(ControllerRegistry, PerAxisGainsGoByAxisName) {
  auto spec = plant_job("seed001", false);
  spec.mutable_controller()->set_name("pid");
  spec.add_axes("left");
  spec.add_axes("right");
  set_axis_gain(*spec.mutable_controller(), "pid", "right", "kd", 4.0);
  const std::string detail = build_contour_job(spec).make_controller()->describe();
  EXPECT_NE(detail.find("pid(kp=540, ki=10800, kd=8) x pid(kp=540, ki=10800, kd=4)"), std::string::npos) << detail;
  rename_axes(spec, {"a", "b"});
  EXPECT_EQ(spec.controller().gains().at("pid").axes().at("b").values().at("kd"), 4.0);
  EXPECT_EQ(build_contour_job(spec).make_controller()->describe(), detail);
  EXPECT_THROW(rename_axes(spec, {"a"}), std::invalid_argument);
  EXPECT_THROW(rename_axes(spec, {"a", "a"}), std::invalid_argument);
}

// Every typed gain message of netmc 0.1 lands in its group (an axis's copy under its axis).
TEST(ControllerRegistry, LegacyFieldsLandInTheirGroups) {
  const auto spec = parse_job_spec_json(R"({"controller": {
      "adrc": {"w0": 1}, "adrcY": {"w0": 2}, "pid": {"kp": 3}, "pid_y": {"kp": 4}, "pidccc": {"kp": 5},
      "ilccc": {"kcp": 6}, "gtcf_adrc": {"wc": 7, "observer_input_delay": 2}, "task_space": {"lambda_c": 8,
      "initialization_filter": true, "ltcf_rotation": false}, "mfa_dtsmc": {"mu": 9, "data_model": "full"},
      "mfa_dtsmc_y": {"mu": 10}, "mfac": {"mu": 11}, "mfac_y": {"mu": 12}, "ffpid_x": {"mass_kg": 13},
      "ffpid_y": {"mass_kg": 14}, "lpccc": {"kp": 15}, "avsc": {"c1": 16},
      "axis_diarc": {"lambda": 17, "exact_dead_zone": {"right_break_v": 1.1}, "lower": [1, 2, 3, 4, 5, 6]}}})",
                                        "test");
  const auto& gains = spec.controller().gains();
  const auto value = [&](const std::string& group, const std::string& key) { return gains.at(group).values().at(key); };
  const auto own = [&](const std::string& group, const std::string& axis, const std::string& key) {
    return gains.at(group).axes().at(axis).values().at(key);
  };
  EXPECT_EQ(value("adrc", "w0"), 1);
  EXPECT_EQ(own("adrc", "y", "w0"), 2);
  EXPECT_EQ(value("pid", "kp"), 3);
  EXPECT_EQ(own("pid", "y", "kp"), 4);
  EXPECT_EQ(value("pidccc", "kp"), 5);
  EXPECT_EQ(value("ilccc", "kcp"), 6);
  EXPECT_EQ(value("gtcf_adrc", "wc"), 7);
  EXPECT_EQ(value("gtcf_adrc", "observer_input_delay"), 2);
  EXPECT_EQ(value("task_space", "lambda_c"), 8);
  EXPECT_EQ(gains.at("task_space").choices().at("initialization_filter"), "on");
  EXPECT_FALSE(gains.at("task_space").choices().contains("ltcf_rotation"));  // false: the default
  EXPECT_EQ(value("mfa_dtsmc", "mu"), 9);
  EXPECT_EQ(gains.at("mfa_dtsmc").choices().at("data_model"), "full");
  EXPECT_EQ(own("mfa_dtsmc", "y", "mu"), 10);
  EXPECT_EQ(value("mfac", "mu"), 11);
  EXPECT_EQ(own("mfac", "y", "mu"), 12);
  // 0.1 ran the data-driven laws on the compact data model unless told: an upgraded spec says so.
  const auto compact = parse_job_spec_json(R"({"controller": {"name": "mfac", "mfac": {"mu": 1}}})", "test");
  EXPECT_EQ(compact.controller().gains().at("mfac").choices().at("data_model"), "compact");
  EXPECT_EQ(own("ffpid", "x", "mass_kg"), 13);
  EXPECT_EQ(own("ffpid", "y", "mass_kg"), 14);
  EXPECT_EQ(value("lpccc", "kp"), 15);
  EXPECT_EQ(value("avsc", "c1"), 16);
  EXPECT_EQ(value("axis_diarc", "lambda"), 17);
  EXPECT_EQ(value("axis_diarc", "right_break_v"), 1.1);
  EXPECT_EQ(gains.at("axis_diarc").lists().at("lower").values_size(), 6);
}

// docs/controllers.md carries the table netmc sim --list-controllers prints (a build with the
// test suite's own controller prints its row too).
TEST(ControllerRegistry, TheDocsTableIsTheRegistrys) {
  std::ifstream file(std::string(NETMC_TEST_DATA_DIR) + "/../../docs/controllers.md");
  ASSERT_TRUE(file) << "docs/controllers.md";
  std::stringstream docs;
  docs << file.rdbuf();
  std::string table;
  std::istringstream lines(ControllerRegistry::global().markdown_table());
  for (std::string line; std::getline(lines, line);) {
    if (line.find("`test-pd`") == std::string::npos) table += line + "\n";
  }
  EXPECT_NE(docs.str().find(table), std::string::npos)
      << "docs/controllers.md lacks the registry's table; netmc sim --list-controllers prints it:\n"
      << table;
}

}  // namespace
}  // namespace netmc::job
