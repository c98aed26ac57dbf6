// netmc sweep: grid expansion (order, values, axes), the tidy CSV's shape, and results that do
// not depend on the number of threads.
#include <gtest/gtest.h>

#include <cmath>

#include <set>
#include <sstream>

#include "client/csv_table.hpp"
#include "client/study_runner.hpp"
#include "client/sweep_grid.hpp"
#include "client/sweep_output.hpp"

namespace netmc::cli {
namespace {

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

// A short grid: 0.5 s per iteration instead of 8 s.
SweepAxes tiny_axes() {
  SweepAxes axes;
  axes.controllers = "adrc,adrc+ilccc";
  axes.delay_max = "1ms,4ms";
  axes.seeds = "1..2";
  axes.fixed.iterations = 3;
  axes.fixed.duration = "0.5s";
  return axes;
}

std::vector<RunOutcome> run_grid(const std::vector<SweepConfiguration>& grid, unsigned threads) {
  StudyPlan plan;
  for (const auto& configuration : grid) plan.jobs.push_back(configuration.job);
  return run_study_in_process(plan, TraceRecording::none, threads);
}

TEST(SweepGrid, RangeAndListAxes) {
  const auto range = parse_value_axis("0.5ms:10ms:20", Quantity::time, "--delay-max");
  ASSERT_EQ(range.size(), 20u);
  for (std::size_t i = 0; i < range.size(); ++i) EXPECT_NEAR(range[i], 0.5e-3 * static_cast<double>(i + 1), 1e-15) << i;
  EXPECT_EQ(parse_value_axis("1ms, 2ms,5ms", Quantity::time, "--delay-max"),
            (std::vector<double>{1e-3, 2e-3, 5e-3}));
  EXPECT_EQ(parse_seed_axis("3..6"), (std::vector<std::uint64_t>{3, 4, 5, 6}));
  EXPECT_EQ(parse_seed_axis("9,2"), (std::vector<std::uint64_t>{9, 2}));
  EXPECT_EQ(parse_seed_axis("7"), (std::vector<std::uint64_t>{7}));
}

TEST(SweepGrid, BadAxisValuesNameTheFlagAndTheForm) {
  const auto delay_error = [](const std::string& text) {
    return error_of([&] { parse_value_axis(text, Quantity::time, "--delay-max"); });
  };
  EXPECT_NE(delay_error("1ms:2ms").find("--delay-max: expected START:STOP:COUNT"), std::string::npos);
  EXPECT_NE(delay_error("1ms:2ms:1").find("--delay-max COUNT: expected an integer from 2"), std::string::npos);
  EXPECT_NE(delay_error("2ms:1ms:3").find("--delay-max: expected STOP above START"), std::string::npos);
  EXPECT_NE(delay_error("1ms:2ms:many").find("--delay-max COUNT"), std::string::npos);
  EXPECT_NE(delay_error("1kg").find("--delay-max: expected a duration"), std::string::npos);
  EXPECT_NE(delay_error(",").find("--delay-max: expected START:STOP:COUNT"), std::string::npos);
  for (const char* seeds : {"5..1", "a..3", "1,x", "-1", ""}) {
    EXPECT_NE(error_of([&] { parse_seed_axis(seeds); }).find("--seeds: expected FIRST..LAST"),
              std::string::npos)
        << seeds;
  }
  SweepAxes axes;
  axes.delay_max = "0.2ms,1ms";
  EXPECT_NE(error_of([&] { expand_sweep(axes); }).find("--delay-max: every value must be at least --delay-min"),
            std::string::npos);
  axes.delay_min = "-1ms";
  EXPECT_NE(error_of([&] { expand_sweep(axes); }).find("--delay-min: expected a non-negative"), std::string::npos);
  axes = {};
  axes.delay_min = "0.1ms";
  EXPECT_NE(error_of([&] { expand_sweep(axes); }).find("--delay-min: only meaningful with --delay-max"),
            std::string::npos);
  axes = {};
  axes.delays = {"constant:1ms"};
  axes.delay_max = "2ms";
  EXPECT_NE(error_of([&] { expand_sweep(axes); }).find("--delay-max: cannot be combined with --delay"),
            std::string::npos);
}

TEST(SweepGrid, ExpandsInGridOrderWithTheLastAxisFastest) {
  const auto grid = expand_sweep(tiny_axes());
  ASSERT_EQ(grid.size(), 2u * 2u * 2u);
  const std::vector<std::tuple<std::string, double, std::uint64_t>> expected{
      {"adrc", 1e-3, 1}, {"adrc", 1e-3, 2}, {"adrc", 4e-3, 1}, {"adrc", 4e-3, 2},
      {"adrc+ilccc", 1e-3, 1}, {"adrc+ilccc", 1e-3, 2}, {"adrc+ilccc", 4e-3, 1}, {"adrc+ilccc", 4e-3, 2}};
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const auto& [label, delay_max, seed] = expected[i];
    EXPECT_EQ(grid[i].number, i + 1);
    EXPECT_EQ(grid[i].base, "seed001");
    EXPECT_EQ(grid[i].label, label);
    EXPECT_EQ(grid[i].job.controller().name(), label);
    ASSERT_TRUE(grid[i].delay_max_s.has_value());
    EXPECT_DOUBLE_EQ(*grid[i].delay_max_s, delay_max);
    EXPECT_DOUBLE_EQ(grid[i].job.downlink().delay().uniform().max_s(), delay_max);
    EXPECT_DOUBLE_EQ(grid[i].job.downlink().delay().uniform().min_s(), 0.3e-3);  // paper 001's bound
    EXPECT_EQ(grid[i].seed, seed);
    EXPECT_EQ(grid[i].job.seed(), seed);
    EXPECT_EQ(grid[i].job.iterations(), 3u);
    EXPECT_DOUBLE_EQ(grid[i].job.duration_s(), 0.5);
  }
}

TEST(SweepGrid, WithoutAxesTheRunsOfThePresetAreTheControllerAxis) {
  SweepAxes axes;
  axes.presets = {"seed001", "seed001-line"};
  axes.seeds = "1,2,3";
  const auto grid = expand_sweep(axes);
  ASSERT_EQ(grid.size(), 2u * 4u * 3u);
  std::set<std::string> labels;
  for (const auto& configuration : grid) labels.insert(configuration.label);
  EXPECT_EQ(labels, (std::set<std::string>{"adrc", "adrc+pidccc", "adrc+ilccc", "adrc+ilccc+q20hz"}));
  EXPECT_EQ(grid.front().base, "seed001");
  EXPECT_EQ(grid.back().base, "seed001-line");
  EXPECT_TRUE(grid.back().job.trajectory().has_line());
  // The preset's own delay, U(0.3, 0.8) ms, is kept and its bound reported.
  EXPECT_DOUBLE_EQ(*grid.front().delay_max_s, 0.8e-3);
  EXPECT_EQ(grid.front().job.iterations(), 20u);
}

TEST(SweepOutput, AThreeAxisRunAddsZColumnsThatTwoAxisRowsLeaveEmpty) {
  std::vector<SweepConfiguration> grid(2);
  std::vector<RunOutcome> outcomes(2);
  for (std::size_t i = 0; i < 2; ++i) {
    grid[i].number = i + 1;
    auto& metrics = *outcomes[i].result.add_iterations();
    for (std::size_t axis = 0; axis < 2 + i; ++axis) metrics.add_tracking_rms_m(1e-6 * static_cast<double>(axis + 1));
  }
  const CsvTable table = CsvTable::parse(sweep_csv(grid, outcomes), "sweep.csv");
  EXPECT_EQ(table.header(), sweep_csv_columns(3));
  ASSERT_EQ(table.rows(), 2u);
  EXPECT_EQ(table.text(0, table.column("tracking_rms_z_m")), "");
  EXPECT_EQ(table.number(1, table.column("tracking_rms_z_m")), 3e-6);
  EXPECT_EQ(table.number(1, table.column("tracking_rms_y_m")), 2e-6);
  // Two-axis grids keep their columns.
  EXPECT_EQ(sweep_csv_columns(2).size() + 4, sweep_csv_columns(3).size());
}

TEST(SweepOutput, CsvHasOneRowPerConfigurationAndIterationWithEveryMetric) {
  const auto grid = expand_sweep(tiny_axes());
  const auto outcomes = run_grid(grid, 2);
  const CsvTable table = CsvTable::parse(sweep_csv(grid, outcomes), "sweep.csv");
  EXPECT_EQ(table.header(), sweep_csv_columns());
  ASSERT_EQ(table.rows(), grid.size() * 3);  // nothing diverges on this grid
  // Every metric of IterationMetrics has its column: per-axis ones split into x and y.
  for (const char* column : {"config", "base", "run", "delay_max_s", "seed", "iteration", "e_max_m",
                             "e_rms_m", "e_sum_m", "e_rms_steady_m", "e_max_steady_m", "tau_mean_s",
                             "tau_p50_s", "tau_p99_s", "tau_max_s", "tau_sc_mean_s", "tau_cc_max_s",
                             "tau_ca_p99_s", "tracking_rms_x_m", "tracking_rms_y_m", "tracking_max_y_m",
                             "command_rms_x", "command_rms_y", "deadline_misses", "lost_feedback",
                             "lost_setpoints", "stale_setpoints", "diverged", "diverged_at_s"}) {
    EXPECT_TRUE(table.has_column(column)) << column;
  }
  const auto* descriptor = netmc::v1::IterationMetrics::descriptor();
  std::size_t metric_columns = 0;
  for (int i = 0; i < descriptor->field_count(); ++i) {
    const auto* field = descriptor->field(i);
    if (field->cpp_type() == google::protobuf::FieldDescriptor::CPPTYPE_MESSAGE) continue;  // estimates: JSON only
    metric_columns += field->is_repeated() ? 2 : 1;
  }
  EXPECT_EQ(table.header().size(), 10 + metric_columns);
  // Rows follow the grid: configuration c holds iterations 1..3, with its own metrics.
  for (std::size_t row = 0; row < table.rows(); ++row) {
    const std::size_t c = row / 3;
    EXPECT_EQ(table.number(row, table.column("config")), static_cast<double>(c + 1));
    EXPECT_EQ(table.number(row, table.column("iteration")), static_cast<double>(row % 3 + 1));
    EXPECT_EQ(table.text(row, table.column("run")), grid[c].label);
    EXPECT_DOUBLE_EQ(table.number(row, table.column("e_max_m")),
                     outcomes[c].result.iterations(static_cast<int>(row % 3)).e_max_m());
    EXPECT_GT(table.number(row, table.column("tau_mean_s")), 0.3e-3);
    EXPECT_LT(table.number(row, table.column("tau_max_s")), *grid[c].delay_max_s + 1e-12);
  }
  // The tidy JSON has the same configurations.
  const std::string json = sweep_json(grid, outcomes);
  EXPECT_NE(json.find("\"config\": 8"), std::string::npos);
  // These runs end before their evaluation window: the steady metrics are absent, not 0.
  EXPECT_EQ(json.find("\"e_max_steady_m\""), std::string::npos);
  EXPECT_TRUE(std::isnan(table.number(0, table.column("e_rms_steady_m"))));
  EXPECT_EQ(table.text(0, table.column("e_rms_steady_m")), "");
}

TEST(SweepOutput, ResultsDoNotDependOnTheThreadCount) {
  const auto grid = expand_sweep(tiny_axes());
  const std::string one = sweep_csv(grid, run_grid(grid, 1));
  const std::string three = sweep_csv(grid, run_grid(grid, 3));
  const std::string eight = sweep_csv(grid, run_grid(grid, 8));
  EXPECT_EQ(one, three);
  EXPECT_EQ(one, eight);
  // ... while the seed does matter (the comparison above could not pass by accident).
  const auto outcomes = run_grid(grid, 2);
  EXPECT_NE(outcomes[0].result.iterations(0).tau_mean_s(), outcomes[1].result.iterations(0).tau_mean_s());
}

}  // namespace
}  // namespace netmc::cli
