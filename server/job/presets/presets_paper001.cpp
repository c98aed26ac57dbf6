// Paper 001's presets (seed001 and its variants): its circle, plant seed001, its controllers.
#include "server/job/presets/preset_studies.hpp"

#include <fmt/format.h>

#include <limits>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "server/job/controller_gains.hpp"

namespace netmc::presets {
namespace {

constexpr std::uint32_t kSeed001Iterations = 20;

// Paper 001's three controllers plus its PD-ILC with a zero-phase Q-filter: the paper's law is
// not monotonically convergent and drifts upwards after some tens of iterations (docs/reproductions/paper-001.md).
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
  job::set_gain(*plan.jobs.back().mutable_controller(), "ilccc", "q_cutoff_hz", kQFilterCutoffHz);
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

// Paper 001, Table 1: its circle and controllers, with the paper's numbers beside them.
StudyPlan seed001() {
  StudyPlan plan = seed001_study("paper 001, Table 1: circle r = 10 mm, h = 5 ms, tau ~ U(0.3, 0.8) ms",
                                 nullptr, nullptr);
  plan.paper = {{"adrc", 0.0811e-3, 77.6556e-3},
                {"adrc+pidccc", 0.0354e-3, 14.1730e-3},
                {"adrc+ilccc", 0.0177e-3, 4.8908e-3}};
  plan.paper_source = "paper 001, Table 1";
  return plan;
}

// Paper 001's plant and gains on a 4:1 ellipse.
StudyPlan seed001_ellipse() {
  netmc::v1::Trajectory t;
  auto& e = *t.mutable_ellipse();
  e.set_semi_axis_x_m(0.020);
  e.set_semi_axis_y_m(0.005);
  e.set_center_x_m(0.050);
  e.set_center_y_m(0.050);
  e.set_period_s(8.0);
  return seed001_study("ellipse a = 20 mm, b = 5 mm (4:1), 8 s, seed001 plant and gains", &t, nullptr);
}

// Paper 001's plant and gains on a straight line.
StudyPlan seed001_line() {
  netmc::v1::Trajectory t;
  auto& l = *t.mutable_line();
  l.set_x0_m(0.040);
  l.set_y0_m(0.040);
  l.set_x1_m(0.080);
  l.set_y1_m(0.060);
  l.set_duration_s(8.0);
  return seed001_study("line (40, 40) -> (80, 60) mm in 8 s, seed001 plant and gains", &t, nullptr);
}

// Paper 001's circle with loop delays beyond one period.
StudyPlan seed001_long_delay() {
  netmc::v1::DelayProfile d;
  d.mutable_uniform()->set_min_s(2e-3);
  d.mutable_uniform()->set_max_s(8e-3);
  return seed001_study("paper 001 circle with tau ~ U(2, 8) ms (beyond one period)", nullptr, &d);
}

// Paper 001's circle with bursty (two-state Markov) loop delays.
StudyPlan seed001_bursty() {
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

}  // namespace netmc::presets
