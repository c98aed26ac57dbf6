// Measures one controller step (ADRC family, task-space, three-axis), the numerical task frame,
// one simulated ILC iteration (1601 cycles), and the seed001 study.
// Run: build/bench/netmc_bench  (e.g. --benchmark_repetitions=5 --benchmark_report_aggregates_only=true)

#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "server/job/presets/presets.hpp"
#include "client/study_runner.hpp"
#include "control/contour_error/contour_error_estimator.hpp"
#include "control/trajectory/circle_trajectory.hpp"
#include "control/axis/adrc_controller.hpp"
#include "control/cross_coupling/contouring_controller.hpp"
#include "control/cross_coupling/iterative_learning_cross_coupling.hpp"
#include "control/task_space/task_space_adrc.hpp"
#include "control/task_space/task_space_diarc.hpp"
#include "control/task_space/task_space_sarc.hpp"
#include "control/trajectory/cubic_spline_curve.hpp"
#include "control/trajectory/ellipse_trajectory.hpp"
#include "control/trajectory/feed_rate_trajectory.hpp"
#include "control/trajectory/heart_trajectory.hpp"
#include "control/trajectory/lissajous_trajectory.hpp"
#include "control/task_space/spatial_sarc.hpp"
#include "control/task_space/task_frame.hpp"
#include "server/job/controller_gains.hpp"
#include "server/job/job_builder.hpp"
#include "server/sim/contour_job_runner.hpp"

namespace {

constexpr double kSamplePeriod = 0.005;   // h = 5 ms
constexpr std::size_t kCycles = 1601;     // 8 s / 5 ms + 1 (k = 0..1600)

// One controller cycle on the paper-001 circle (centre (50, 50) mm, r = 10 mm, 8 s) with paper
// 001's default gains. References and measurements are precomputed so only step() is timed; the
// measured position sits a fixed (0.1, -0.05) mm off the reference. The cycle index k wraps at
// 1601; at each wrap end_iteration() + begin_iteration() are called inside the timed loop (once
// per 1601 steps, so their cost, including the ILC memory update, is amortized into the figure).
void control_step(benchmark::State& state, const std::string& controller_name) {
  const netmc::control::CircleTrajectory circle({{0.05, 0.05}, 0.01, 8.0});
  std::vector<netmc::control::ReferencePoint> references(kCycles);
  std::vector<Eigen::Vector2d> measured(kCycles);
  for (std::size_t k = 0; k < kCycles; ++k) {
    references[k] = circle.sample(static_cast<double>(k) * kSamplePeriod);
    measured[k] = references[k].position + Eigen::Vector2d(1e-4, -5e-5);
  }
  // Paper 001's laws with its gains, as the registry composes adrc and adrc+ilccc.
  namespace c = netmc::control;
  std::unique_ptr<c::ContourCompensator> compensator = std::make_unique<c::NoContourCompensation>();
  if (controller_name == "adrc+ilccc") {
    compensator = std::make_unique<c::IterativeLearningCrossCoupling>(c::IterativeLearningGains{}, kSamplePeriod);
  }
  c::ContouringController controller(std::make_unique<c::AdrcController>(c::AdrcGains{}, kSamplePeriod),
                                     std::make_unique<c::AdrcController>(c::AdrcGains{}, kSamplePeriod),
                                     c::make_contour_error_estimator("curvature"), std::move(compensator));
  const Eigen::Vector2d start = references[0].position;
  controller.begin_iteration(start, kCycles);

  std::size_t k = 0;
  for (auto _ : state) {
    auto cycle = controller.step(k, references[k], measured[k]);
    benchmark::DoNotOptimize(cycle);
    if (++k == kCycles) {
      k = 0;
      controller.end_iteration();
      controller.begin_iteration(start, kCycles);
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

// One in-loop contour-error estimate on paper 002's heart (netmc's assumed size and period): the axis lags the
// desired point by 10 ms along the path and sits 50 um off it, a fresh desired time each call
// (2000 along the period). `netmc cee` explains the order: the cost follows curve evaluations.
void contour_error_estimate(benchmark::State& state, const char* estimator_name) {
  const auto heart = std::make_shared<netmc::control::HeartTrajectory>(netmc::control::HeartParameters{});
  constexpr std::size_t kPoints = 2000;
  std::vector<netmc::control::ReferencePoint> references(kPoints);
  std::vector<Eigen::Vector2d> measured(kPoints);
  for (std::size_t i = 0; i < kPoints; ++i) {
    const double t = 0.02 + 9.9 * static_cast<double>(i) / kPoints;
    references[i] = heart->sample(t);
    references[i].time_s = t;
    const auto lagging = heart->sample(t - 0.01);
    const Eigen::Vector2d normal = Eigen::Vector2d(lagging.velocity.y(), -lagging.velocity.x()).normalized();
    measured[i] = lagging.position + 5e-5 * normal;
  }
  const auto estimator = netmc::control::make_contour_error_estimator(estimator_name, heart);
  std::size_t i = 0;
  for (auto _ : state) {
    auto estimate = estimator->estimate(references[i], measured[i]);
    benchmark::DoNotOptimize(estimate);
    if (++i == kPoints) i = 0;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
void BM_ContourErrorEstimate_Heart_Tangent(benchmark::State& state) { contour_error_estimate(state, "tangent"); }
void BM_ContourErrorEstimate_Heart_Newton(benchmark::State& state) { contour_error_estimate(state, "newton"); }
void BM_ContourErrorEstimate_Heart_Steffensen(benchmark::State& state) {
  contour_error_estimate(state, "steffensen");
}

void BM_ControlStep_AdrcIlccc_TwoAxes(benchmark::State& state) { control_step(state, "adrc+ilccc"); }
void BM_ControlStep_Adrc_TwoAxes(benchmark::State& state) { control_step(state, "adrc"); }

// Iterations of `spec`'s job, one per benchmark iteration, on one runner.
void simulated_iterations(benchmark::State& state, const netmc::v1::JobSpec& spec) {
  netmc::sim::ContourJob job = netmc::job::build_contour_job(spec);
  job.iterations = 100'000;  // more than a benchmark run reaches, within a job's work ceiling
  netmc::sim::ContourJobRunner runner(std::move(job));
  for (auto _ : state) {
    auto record = runner.run_iteration();
    if (record.metrics.diverged) {
      state.SkipWithError("simulated iteration diverged");
      break;
    }
    benchmark::DoNotOptimize(record);
  }
  state.counters["cycles_per_second"] = benchmark::Counter(
      static_cast<double>(kCycles), benchmark::Counter::kIsIterationInvariantRate);
}

netmc::v1::JobSpec seed001_q_filtered_ilc() {
  auto spec = netmc::presets::seed001_job("adrc+ilccc");
  netmc::job::set_gain(*spec.mutable_controller(), "ilccc", "q_cutoff_hz", 20.0);
  return spec;
}

// One full ILC iteration (1601 cycles: plants, sensors, delayed links, controller, metrics) of
// the seed001 adrc+ilccc job. The runner is built once; each benchmark iteration is the next ILC
// iteration. The Q-filtered law is used because the paper's law drifts unstable after ~100
// iterations (docs/reproductions/paper-001.md), which a long benchmark run would reach.
void BM_SimulatedIteration_Seed001_AdrcIlccc(benchmark::State& state) {
  simulated_iterations(state, seed001_q_filtered_ilc());
}

// The same iteration behind a constant 20 ms downlink with --compensate predictor: the cost of
// the delay compensation (an observer step and a prediction over 20 ms of the friction model per
// axis and cycle, the playout at the axes).
void BM_SimulatedIteration_Seed001_AdrcIlccc_Predictor20ms(benchmark::State& state) {
  auto spec = seed001_q_filtered_ilc();
  spec.mutable_downlink()->mutable_delay()->mutable_uniform()->set_min_s(0.020);
  spec.mutable_downlink()->mutable_delay()->mutable_uniform()->set_max_s(0.020);
  spec.mutable_compensation()->set_name("predictor");
  simulated_iterations(state, spec);
}

// The same with predictor+packets:horizon=8: a copy of the controller each cycle (with ILC's
// memory) run 7 periods ahead on the model, and the axes' playout of the horizons.
void BM_SimulatedIteration_Seed001_AdrcIlccc_PredictorPackets20ms(benchmark::State& state) {
  auto spec = seed001_q_filtered_ilc();
  spec.mutable_downlink()->mutable_delay()->mutable_uniform()->set_min_s(0.020);
  spec.mutable_downlink()->mutable_delay()->mutable_uniform()->set_max_s(0.020);
  spec.mutable_compensation()->set_name("predictor+packets");
  spec.mutable_compensation()->set_horizon(8);
  simulated_iterations(state, spec);
}

// The whole default study: 4 runs (adrc, adrc+pidccc, adrc+ilccc, adrc+ilccc+q20hz) x 20
// iterations, in process, on `threads` worker threads. The all-cores variant reports wall-clock
// time (UseRealTime): the CPU time of the calling thread alone would understate the work.
void seed001_study(benchmark::State& state, unsigned threads) {
  const netmc::presets::StudyPlan plan = netmc::presets::make_preset("seed001");
  for (auto _ : state) {
    auto outcomes = netmc::cli::run_study_in_process(plan, netmc::cli::TraceRecording::none, threads);
    benchmark::DoNotOptimize(outcomes);
  }
  state.counters["threads"] = static_cast<double>(threads);
}

void BM_Seed001Study_20Iterations(benchmark::State& state) { seed001_study(state, 1); }
void BM_Seed001Study_20Iterations_AllCores(benchmark::State& state) {
  const unsigned cores = std::thread::hardware_concurrency();
  seed001_study(state, cores == 0 ? 1 : cores);
}

}  // namespace

// One evaluation of the numerical global task frame (exact foot point: the sampled-run search,
// then safeguarded Newton), as the GTCF controller does twice per cycle, at points 50 um off a
// closed spline driven at a feed (the costliest reference to sample) and off a Lissajous figure.
void numerical_frame(benchmark::State& state, const netmc::control::ReferenceTrajectory& contour) {
  const netmc::control::NumericalTaskFrame frame(std::shared_ptr<const netmc::control::ReferenceTrajectory>(contour.clone()));
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 1000; ++i) {
    const auto c = contour.sample(contour.duration_s() * (i + 0.5) / 1000);
    points.push_back(c.position + 5e-5 * Eigen::Vector2d(c.velocity.y(), -c.velocity.x()).normalized());
  }
  std::size_t i = 0;
  for (auto _ : state) {
    auto r = frame.at(points[i]);
    benchmark::DoNotOptimize(r);
    if (++i == points.size()) i = 0;
  }
}

void BM_NumericalTaskFrame_Spline(benchmark::State& state) {
  const std::vector<Eigen::Vector2d> points{{0.05, 0.05}, {0.08, 0.045}, {0.1, 0.06}, {0.09, 0.08},
                                            {0.07, 0.07}, {0.055, 0.085}, {0.04, 0.065}, {0.05, 0.05}};
  const netmc::control::FeedRateTrajectory spline(std::make_shared<netmc::control::CubicSplineCurve>(points),
                                                  {0.01, 0.02, 0.02});
  numerical_frame(state, spline);
}

void BM_NumericalTaskFrame_Lissajous(benchmark::State& state) {
  const netmc::control::LissajousTrajectory figure({{0.05, 0.05}, 0.02, 0.015, 3, 2, 0.3, 20.0});
  numerical_frame(state, figure);
}

// One cycle of a task-space controller at the thesis's h = 0.2 ms (a 200 us budget) on the
// thesis ellipse (x = 0.2 sin 7t, y = 0.02 - 0.02 cos 7t), the measured position 3 um off the
// reference along the normal; closed-form frame for gtcf-*, the desired point's tangent for ltcf-*.
void task_space_step(benchmark::State& state, const std::string& controller_name) {
  constexpr double h = 2e-4;
  netmc::control::EllipseParameters parameters;
  parameters.center = {0.0, 0.02};
  parameters.semi_axis_x_m = 0.2;
  parameters.semi_axis_y_m = 0.02;
  parameters.period_s = 2.0 * std::numbers::pi / 7.0;
  parameters.start_angle_rad = -std::numbers::pi / 2.0;
  const netmc::control::EllipseTrajectory ellipse(parameters);
  const std::size_t cycles = static_cast<std::size_t>(ellipse.duration_s() / h);
  std::vector<netmc::control::ReferencePoint> references(cycles);
  std::vector<Eigen::Vector2d> measured(cycles);
  for (std::size_t k = 0; k < cycles; ++k) {
    references[k] = ellipse.sample(static_cast<double>(k) * h);
    const Eigen::Vector2d v = references[k].velocity;
    measured[k] = references[k].position + 3e-6 * Eigen::Vector2d(-v.y(), v.x()).normalized();
  }
  // The laws with the thesis's gains, in the ellipse's global frame or the local one.
  namespace c = netmc::control;
  std::unique_ptr<c::ContourController> controller;
  if (controller_name == "ltcf-sarc") controller = std::make_unique<c::TaskSpaceSarc>(c::SarcGains{}, h, nullptr);
  if (controller_name == "gtcf-sarc") {
    controller = std::make_unique<c::TaskSpaceSarc>(c::SarcGains{}, h, c::make_task_frame(ellipse));
  }
  if (controller_name == "gtcf-diarc") {
    controller = std::make_unique<c::TaskSpaceDiarc>(c::DiarcGains{}, h, c::make_task_frame(ellipse));
  }
  if (controller_name == "gtcf-adrc") {
    controller = std::make_unique<c::TaskSpaceAdrc>(c::GtcfAdrcGains{}, h, c::make_task_frame(ellipse));
  }
  controller->begin_iteration(references[0].position, cycles);
  std::size_t k = 0;
  for (auto _ : state) {
    auto cycle = controller->step(k, references[k], measured[k]);
    benchmark::DoNotOptimize(cycle);
    if (++k == cycles) {
      k = 0;
      controller->begin_iteration(references[0].position, cycles);
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void BM_ControlStep_GtcfSarc(benchmark::State& state) { task_space_step(state, "gtcf-sarc"); }
void BM_ControlStep_LtcfSarc(benchmark::State& state) { task_space_step(state, "ltcf-sarc"); }
void BM_ControlStep_GtcfDiarc(benchmark::State& state) { task_space_step(state, "gtcf-diarc"); }
void BM_ControlStep_GtcfAdrc(benchmark::State& state) { task_space_step(state, "gtcf-adrc"); }

// One cycle of three-axis GTCF-SARC (thesis ch. 6) on a tilted 50 mm circle, 3 um off it.
void BM_ControlStep_SpatialSarc_ThreeAxes(benchmark::State& state) {
  constexpr double h = 2e-4;
  netmc::control::SpatialCircleParameters parameters;
  parameters.center = {0.10, 0.10, 0.05};
  parameters.normal = {-1.0, 1.0, 0.5};
  parameters.period_s = 2.0 * std::numbers::pi / 4.0;
  auto circle = std::make_shared<netmc::control::SpatialCircle>(parameters);
  netmc::control::SpatialSarc controller({}, h, circle);
  const auto cycles = static_cast<std::size_t>(parameters.period_s / h);
  std::vector<netmc::control::SpatialReferencePoint> references(cycles);
  std::vector<Eigen::Vector3d> measured(cycles);
  for (std::size_t k = 0; k < cycles; ++k) {
    references[k] = circle->sample(static_cast<double>(k) * h);
    measured[k] = references[k].position + 3e-6 * (references[k].position - parameters.center).normalized();
  }
  controller.begin(references[0].position);
  std::size_t k = 0;
  for (auto _ : state) {
    auto u = controller.step(references[k], measured[k]);
    benchmark::DoNotOptimize(u);
    if (++k == cycles) k = 0;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

BENCHMARK(BM_ContourErrorEstimate_Heart_Tangent);
BENCHMARK(BM_ContourErrorEstimate_Heart_Newton);
BENCHMARK(BM_ContourErrorEstimate_Heart_Steffensen);
BENCHMARK(BM_ControlStep_AdrcIlccc_TwoAxes);
BENCHMARK(BM_ControlStep_GtcfSarc);
BENCHMARK(BM_ControlStep_LtcfSarc);
BENCHMARK(BM_ControlStep_GtcfDiarc);
BENCHMARK(BM_ControlStep_GtcfAdrc);
BENCHMARK(BM_ControlStep_SpatialSarc_ThreeAxes);
BENCHMARK(BM_ControlStep_Adrc_TwoAxes);
BENCHMARK(BM_NumericalTaskFrame_Spline);
BENCHMARK(BM_NumericalTaskFrame_Lissajous);
BENCHMARK(BM_SimulatedIteration_Seed001_AdrcIlccc)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SimulatedIteration_Seed001_AdrcIlccc_Predictor20ms)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SimulatedIteration_Seed001_AdrcIlccc_PredictorPackets20ms)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Seed001Study_20Iterations)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Seed001Study_20Iterations_AllCores)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
