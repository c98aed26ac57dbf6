// Paper 004's preset (seed004): the H-bridge stage and its cross-coupling laws.
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

// Paper 004, Table 4 (section 4): the H-bridge stage (stage004), the per-axis loops of
// eq. 2 with 85 % acceleration feedforward, uncoupled and with the two cross-coupling laws
// (eq. 13 with Table 3, eq. 20) at 20 kHz (Tustin), the plant integrated at 100 kHz. The metric
// is the contour error's RMS over the whole run, settling included (the window opens at the
// first period). netmc's assumptions [A] (section 4 prints "r = 1/5 pi m" and no speed): the circle
// r = 1/(5 pi) m, one revolution in 2 s with 0.2 s quintic angle ramps, then 0.5 s holding the end
// point; the sharp angle (0, 0) -> (0.1, 0) -> (0.1, 0.1) m at 0.1 m/s, stopping at the corner,
// then 0.5 s holding.
// The paper gives no acceleration or jerk limit for the sharp angle: 1 m/s^2 and 10 m/s^3 here
// (the circle's peak is 0.78 m/s^2).
constexpr double kSeed004SamplePeriodS = 5e-5;
constexpr double kSeed004SettlingS = 0.5;

netmc::v1::JobSpec seed004_job(const netmc::v1::Trajectory& trajectory, double trajectory_duration_s,
                               const std::string& controller, const std::string& label) {
  netmc::v1::JobSpec job;
  job.set_name(label);
  *job.mutable_trajectory() = trajectory;
  job.set_plant("stage004");
  job.mutable_controller()->set_name(controller);
  job.mutable_controller()->set_estimator("tangent");  // paper 004, eq. 3
  job.set_sample_period_s(kSeed004SamplePeriodS);
  job.set_duration_s(trajectory_duration_s + kSeed004SettlingS);
  job.set_evaluation_start_s(kSeed004SamplePeriodS);
  job.set_iterations(1);
  job.set_seed(1);
  return job;
}

}  // namespace

StudyPlan seed004() {
  StudyPlan plan;
  plan.title = "paper 004, Table 4: H-bridge stage, ffpid per axis (eq. 2, 85 % feedforward), cross-coupling eq. 13 "
               "(lpccc) and eq. 20 (qftccc), h = 0.05 ms; circle r = 1/(5 pi) m in 2 s and the sharp angle at 0.1 m/s, "
               "each with 0.5 s settling; RMS over the whole run";
  plan.steady_metrics = true;
  plan.paper = {{"circle ffpid", 2.53e-6, std::numeric_limits<double>::quiet_NaN()},
                {"circle ffpid+lpccc", 1.15e-6, std::numeric_limits<double>::quiet_NaN()},
                {"circle ffpid+qftccc", 0.74e-6, std::numeric_limits<double>::quiet_NaN()},
                {"sharp ffpid", 5.66e-6, std::numeric_limits<double>::quiet_NaN()},
                {"sharp ffpid+lpccc", 6.06e-6, std::numeric_limits<double>::quiet_NaN()},
                {"sharp ffpid+qftccc", 4.07e-6, std::numeric_limits<double>::quiet_NaN()}};
  plan.paper_source = "paper 004, Table 4 (its shifted sharp-angle labels read as uncoupled, PID-type, QFT-type)";

  netmc::v1::Trajectory circle;
  auto& c = *circle.mutable_circle();
  c.set_radius_m(1.0 / (5.0 * std::numbers::pi));
  c.set_period_s(2.0);
  c.set_ramp_s(0.2);
  netmc::v1::Trajectory sharp;
  auto& p = *sharp.mutable_polyline();
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, std::pair{0.1, 0.0}, std::pair{0.1, 0.1}}) {
    auto& point = *p.add_points();
    point.set_x_m(x);
    point.set_y_m(y);
  }
  p.set_max_speed_m_s(0.1);
  p.set_max_acceleration_m_s2(1.0);
  p.set_max_jerk_m_s3(10.0);
  // One segment: 0.2 s accelerating (jerk phases of 0.1 s each, peak 1 m/s^2), 0.8 s cruising,
  // 0.2 s decelerating.
  constexpr double kSharpDurationS = 2 * 1.2;
  for (const auto& [trajectory, duration_s, name] :
       {std::tuple{&circle, 2.0, "circle"}, std::tuple{&sharp, kSharpDurationS, "sharp"}}) {
    for (const char* controller : {"ffpid", "ffpid+lpccc", "ffpid+qftccc"}) {
      plan.jobs.push_back(seed004_job(*trajectory, duration_s, controller, std::string(name) + " " + controller));
    }
  }
  return plan;
}

}  // namespace netmc::presets
