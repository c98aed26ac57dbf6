#include "client/presets.hpp"

#include <numbers>
#include <stdexcept>

namespace netmc::cli {
namespace {

constexpr std::uint32_t kSeed001Iterations = 20;

// Paper 001's three controllers plus its PD-ILC with a zero-phase Q-filter: the paper's law is
// not monotonically convergent and drifts upwards after some tens of iterations (README).
constexpr double kQFilterCutoffHz = 20.0;

StudyPlan seed001_study(const std::string& title, const netmc::v1::Trajectory* trajectory,
                        const netmc::v1::DelayProfile* delay) {
  StudyPlan plan;
  plan.title = title;
  for (const char* controller : {"adrc", "adrc+pidccc", "adrc+ilccc", "adrc+ilccc"}) {
    auto job = seed001_job(controller);
    if (trajectory) *job.mutable_trajectory() = *trajectory;
    if (delay) *job.mutable_downlink()->mutable_delay() = *delay;
    plan.jobs.push_back(job);
  }
  plan.jobs.back().set_name("adrc+ilccc+q20hz");
  plan.jobs.back().mutable_controller()->mutable_ilccc()->set_q_cutoff_hz(kQFilterCutoffHz);
  return plan;
}

}  // namespace

netmc::v1::JobSpec seed001_job(const std::string& controller) {
  netmc::v1::JobSpec job;
  auto& circle = *job.mutable_trajectory()->mutable_circle();
  circle.set_radius_m(0.010);
  circle.set_center_x_m(0.050);
  circle.set_center_y_m(0.050);
  circle.set_period_s(8.0);
  job.set_plant("seed001");
  job.mutable_controller()->set_name(controller);
  auto& delay = *job.mutable_downlink()->mutable_delay()->mutable_uniform();
  delay.set_min_s(0.3e-3);
  delay.set_max_s(0.8e-3);
  job.set_sample_period_s(0.005);
  job.set_iterations(kSeed001Iterations);
  job.set_seed(1);
  return job;
}

std::vector<std::string> preset_names() {
  return {"seed001", "seed001-ellipse", "seed001-line", "seed001-long-delay", "seed001-bursty",
          "thesis-ellipse", "thesis-circle"};
}

namespace {

// Thesis (paper 000) eq. 2-68: x = 0.2 sin 7t, y = -0.02 cos 7t + 0.02 for 25 s, linear-motor
// stage, Ts = 0.2 ms, 0.5 um encoder, no network; metrics over 10-25 s (digest 2.12 [A]).
// Both thesis chapter-2 studies: LTCF-SARC against GTCF-SARC on the linear-motor stage.
StudyPlan thesis_study(const std::string& title, const netmc::v1::Trajectory& trajectory,
                       std::vector<PaperRow> paper, const std::string& source) {
  StudyPlan plan;
  plan.title = title;
  plan.steady_metrics = true;
  for (const char* controller : {"ltcf-sarc", "gtcf-sarc"}) {
    netmc::v1::JobSpec job;
    *job.mutable_trajectory() = trajectory;
    job.set_plant("linmotor");
    job.mutable_controller()->set_name(controller);
    job.set_sample_period_s(2e-4);
    job.mutable_sensor()->set_resolution_m(0.5e-6);
    job.set_evaluation_start_s(10.0);
    job.set_iterations(1);
    job.set_seed(1);
    plan.jobs.push_back(job);
  }
  plan.paper = std::move(paper);
  plan.paper_source = source;
  return plan;
}

// Case D of Table 2-2: as C, but the reference halts for 4 ms at t = 6 pi s (digest 2.12 [A]).
// The drive's command is limited to the +-10 V of the thesis's DAC (linear to about 8 V,
// appendix A): without a limit the halt asks for a 700 V spike that no stage could apply.
constexpr double kThesisCommandLimit = 10.0;

StudyPlan thesis_ellipse() {
  netmc::v1::Trajectory t;
  auto& e = *t.mutable_ellipse();
  e.set_semi_axis_x_m(0.2);
  e.set_semi_axis_y_m(0.02);
  e.set_center_x_m(0.0);
  e.set_center_y_m(0.02);
  e.set_period_s(2.0 * std::numbers::pi / 7.0);
  e.set_start_angle_rad(-std::numbers::pi / 2.0);
  e.set_revolutions(25.0 * 7.0 / (2.0 * std::numbers::pi));  // 25 s
  StudyPlan plan = thesis_study(
      "thesis Table 2-2: 10:1 ellipse at 7 rad/s, linear motors, Ts = 0.2 ms; case D halts 4 ms at 6 pi s",
      t,
      {{"ltcf-sarc", 5.66e-6, 22.37e-6},
       {"gtcf-sarc", 2.20e-6, 6.73e-6},
       {"ltcf-sarc (D)", 5.76e-6, 68.50e-6},
       {"gtcf-sarc (D)", 2.29e-6, 23.43e-6}},
      "thesis Table 2-2");
  const std::size_t case_c_runs = plan.jobs.size();
  for (std::size_t i = 0; i < case_c_runs; ++i) {
    netmc::v1::JobSpec halted = plan.jobs[i];
    halted.set_name(halted.controller().name() + " (D)");
    auto& halt = *halted.mutable_trajectory()->mutable_halt();
    halt.set_at_s(6.0 * std::numbers::pi);
    halt.set_duration_s(0.004);
    plan.jobs.push_back(halted);
  }
  for (auto& job : plan.jobs) job.set_command_limit(kThesisCommandLimit);
  return plan;
}

// Thesis eq. 2-65 (case A, zero initial error): x = 0.04 sin 15t, y = -0.04 cos 15t + 0.04,
// 30 s, metrics over 10-30 s.
StudyPlan thesis_circle() {
  netmc::v1::Trajectory t;
  auto& c = *t.mutable_circle();
  c.set_radius_m(0.04);
  c.set_center_x_m(0.0);
  c.set_center_y_m(0.04);
  c.set_period_s(2.0 * std::numbers::pi / 15.0);
  c.set_start_angle_rad(-std::numbers::pi / 2.0);
  c.set_revolutions(30.0 * 15.0 / (2.0 * std::numbers::pi));  // 30 s
  return thesis_study("thesis Table 2-1 (case A): circle r = 4 cm at 15 rad/s, linear motors, Ts = 0.2 ms", t,
                      {{"ltcf-sarc", 13.33e-6, 31.54e-6}, {"gtcf-sarc", 9.92e-6, 25.89e-6}},
                      "thesis Table 2-1 (A)");
}

}  // namespace

StudyPlan make_preset(std::string_view name) {
  if (name == "seed001") {
    StudyPlan plan = seed001_study("paper 001, Table 1: circle r = 10 mm, h = 5 ms, tau ~ U(0.3, 0.8) ms",
                                   nullptr, nullptr);
    plan.paper = {{"adrc", 0.0811e-3, 77.6556e-3},
                  {"adrc+pidccc", 0.0354e-3, 14.1730e-3},
                  {"adrc+ilccc", 0.0177e-3, 4.8908e-3}};
    plan.paper_source = "paper 001, Table 1";
    return plan;
  }
  if (name == "seed001-ellipse") {
    netmc::v1::Trajectory t;
    auto& e = *t.mutable_ellipse();
    e.set_semi_axis_x_m(0.020);
    e.set_semi_axis_y_m(0.005);
    e.set_center_x_m(0.050);
    e.set_center_y_m(0.050);
    e.set_period_s(8.0);
    return seed001_study("ellipse a = 20 mm, b = 5 mm (4:1), 8 s, seed001 plant and gains", &t, nullptr);
  }
  if (name == "seed001-line") {
    netmc::v1::Trajectory t;
    auto& l = *t.mutable_line();
    l.set_x0_m(0.040);
    l.set_y0_m(0.040);
    l.set_x1_m(0.080);
    l.set_y1_m(0.060);
    l.set_duration_s(8.0);
    return seed001_study("line (40, 40) -> (80, 60) mm in 8 s, seed001 plant and gains", &t, nullptr);
  }
  if (name == "seed001-long-delay") {
    netmc::v1::DelayProfile d;
    d.mutable_uniform()->set_min_s(2e-3);
    d.mutable_uniform()->set_max_s(8e-3);
    return seed001_study("paper 001 circle with tau ~ U(2, 8) ms (beyond one period)", nullptr, &d);
  }
  if (name == "seed001-bursty") {
    netmc::v1::DelayProfile d;
    auto& m = *d.mutable_markov();
    m.mutable_good()->set_min_s(0.3e-3);
    m.mutable_good()->set_max_s(0.8e-3);
    m.mutable_bad()->set_min_s(3e-3);
    m.mutable_bad()->set_max_s(12e-3);
    m.set_p_good_to_bad(0.02);
    m.set_p_bad_to_good(0.2);
    return seed001_study("paper 001 circle with bursty Markov delay (good 0.3-0.8 ms, bad 3-12 ms)",
                         nullptr, &d);
  }
  if (name == "thesis-ellipse") return thesis_ellipse();
  if (name == "thesis-circle") return thesis_circle();
  std::string expected;
  for (const auto& n : preset_names()) expected += (expected.empty() ? "" : ", ") + n;
  throw std::invalid_argument("--preset: unknown name '" + std::string(name) +
                              "' (expected one of: " + expected + ")");
}

}  // namespace netmc::cli
