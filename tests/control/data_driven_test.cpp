// Paper 002's building blocks: the data-model estimators (eq. 11-14) against a plant that is
// exactly their data model, and the reaching law (eq. 18-20) against the reaching conditions;
// the full-form (L_y = 2, d = 1) data model against eq. 2; and both laws in the contouring
// composition on eq. 2 and on the ballscrew plant (the exact sampled eq. 1).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "control/contour_error/contour_error_estimator.hpp"
#include "control/data_driven/compact_form_mfac.hpp"
#include "control/data_driven/data_driven_contouring.hpp"
#include "control/data_driven/data_model_estimator.hpp"
#include "control/data_driven/mfa_dtsmc_axis.hpp"
#include "control/data_driven/terminal_sliding_mode.hpp"
#include "control/trajectory/circle_trajectory.hpp"
#include "netsim/random_stream.hpp"
#include "plant/ball_screw_drive.hpp"

namespace netmc::control {
namespace {

// y(k+1) = y(k) + Phi du(k) + Psi dd(k) with constant Phi, Psi (eq. 9 with known derivatives).
struct KnownDataModel {
  double phi, psi;
};

TEST(DataModelEstimator, PhiConvergesToTheTrueDerivativeUnderExcitation) {
  const KnownDataModel plant{30.0, 10.0};
  DataModelEstimator estimator({});
  netsim::RandomStream random(7);
  double previous_du = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const double dy = plant.phi * previous_du;  // no disturbance
    estimator.update(dy, previous_du);
    previous_du = random.uniform(-1.0, 1.0);
  }
  EXPECT_NEAR(estimator.phi(), plant.phi, 0.05);
  EXPECT_NEAR(estimator.disturbance_increment(), 0.0, 1e-3);
}

TEST(DataModelEstimator, PredictionErrorShrinksWithAnUnknownDisturbance) {
  // A slow sinusoidal disturbance the estimator does not see: kappa must come to explain dy.
  const KnownDataModel plant{30.0, 10.0};
  DataModelEstimator estimator({});
  netsim::RandomStream random(11);
  double previous_du = 0.0, previous_d = 0.0;
  double early = 0.0, late = 0.0, late_dy = 0.0;
  for (int k = 1; k <= 4000; ++k) {
    const double d = 0.2 * std::sin(2.0 * 3.141592653589793 * k / 500.0);
    const double dy = plant.phi * previous_du + plant.psi * (d - previous_d);
    const double predicted = estimator.psi() * estimator.disturbance_increment() + estimator.phi() * previous_du;
    const double residual = std::abs(dy - predicted);
    if (k <= 200) early += residual;
    if (k > 3800) {
      late += residual;
      late_dy += std::abs(dy);
    }
    estimator.update(dy, previous_du);
    previous_du = 0.05 * random.uniform(-1.0, 1.0);
    previous_d = d;
  }
  EXPECT_LT(late, 0.5 * early);
  EXPECT_LT(late, 0.5 * late_dy);
}

TEST(DataModelEstimator, ResetsFollowSection32) {
  DataModelEstimatorGains gains;
  gains.phi_initial = 18.0;
  DataModelEstimator estimator(gains);
  estimator.update(100.0, 1.0);  // moves Phi^ away from 18
  ASSERT_NE(estimator.phi(), 18.0);
  estimator.update(1.0, 0.0);  // |du| <= epsilon: back to Phi^(1)
  EXPECT_EQ(estimator.phi(), 18.0);
  // |dd^| >= 2 d0: dd^ and d^ back to 0.
  gains.disturbance_bound = 1e-3;
  DataModelEstimator small_bound(gains);
  small_bound.update(1000.0, 0.0);
  EXPECT_EQ(small_bound.disturbance_increment(), 0.0);
  EXPECT_EQ(small_bound.disturbance(), 0.0);
}

TEST(DataModelEstimator, RejectsGainsOutsideTheirRanges) {
  DataModelEstimatorGains gains;
  gains.eta = 1.5;
  EXPECT_THROW(DataModelEstimator{gains}, std::invalid_argument);
  gains = {};
  gains.rho = 0.0;
  EXPECT_THROW(DataModelEstimator{gains}, std::invalid_argument);
}

TEST(TerminalSlidingMode, SlidingVariableIsEquation17) {
  TerminalSlidingModeGains g;  // paper 002's C4: lambda1 0.3, lambda2 0.2, alpha 5/7, beta 0.75
  const TerminalSlidingMode mode(g, 1e-3);
  const double e = 3.0, previous = -2.0;
  const double expected = 0.3 * 3.0 + 0.2 * -std::pow(2.0, 5.0 / 7.0) - 0.3 * 0.25 * -2.0;
  EXPECT_NEAR(mode.sliding_variable(e, previous), expected, 1e-14);
  EXPECT_EQ(signed_power(-8.0, 1.0 / 3.0), -2.0);
}

TEST(TerminalSlidingMode, ReachingLawMeetsTheReachingConditions) {
  const TerminalSlidingModeGains g;
  const TerminalSlidingMode mode(g, 1e-3);
  // Outside the quasi-sliding band |s| <= lambda cosh(delta2 s) / (1 + E1) (~0.03 here), eq. 65-70:
  // E1 in (0, 1), E2 >= lambda, (s(k+1) - s(k)) sgn s < 0 and (s(k+1) + s(k)) sgn s > 0.
  for (double magnitude = 0.05; magnitude < 1e5; magnitude *= 1.3) {
    for (double s : {magnitude, -magnitude}) {
      EXPECT_GT(mode.e1(s), 0.0);
      EXPECT_LT(mode.e1(s), 1.0);
      EXPECT_GE(mode.e2(s), g.lambda);
      const double next = mode.next_sliding_variable(s);
      const double sign = s > 0 ? 1.0 : -1.0;
      EXPECT_LT((next - s) * sign, 0.0) << s;
      EXPECT_GT((next + s) * sign, 0.0) << s;
    }
  }
  // Inside the band the law only holds s at the band: |s(k+1)| <= lambda cosh(delta2 s).
  EXPECT_LE(std::abs(mode.next_sliding_variable(0.01)), g.lambda * std::cosh(g.delta2 * 0.01));
}

TEST(TerminalSlidingMode, RejectsAContractionOutsideTheUnitInterval) {
  TerminalSlidingModeGains g;
  g.q = 2000.0;  // 1 - qT = -1 at T = 1 ms
  EXPECT_THROW(TerminalSlidingMode(g, 1e-3), std::invalid_argument);
}

// ---- the full-form data model and the coupled composition ----

// Paper 002, eq. 2 in um and V: y(k+2) = 1.68125 y(k+1) - 0.68125 y(k) + 18 (u(k) + d(k)).
struct Equation2 {
  double y0 = 0.0, y1 = 0.0;  // y(k), y(k+1)
  void reset(double y) { y0 = y1 = y; }
  void step(double u) {
    const double y2 = 1.68125 * y1 - 0.68125 * y0 + 18.0 * u;
    y0 = y1;
    y1 = y2;
  }
};

TEST(FullFormDataModel, ConvergesToEquation2UnderExcitation) {
  FullFormDataModelGains gains;  // paper 002's C4 eta 0.8, mu 0.5; prior a = (2, -1)
  gains.b0_initial = 10.0;       // away from the true 18
  FullFormDataModel model(gains);
  Equation2 plant;
  netsim::RandomStream random(5);
  double u = 0.0, previous_y = 0.0;
  for (int k = 0; k < 5000; ++k) {
    const double y = plant.y0;
    model.update(y - previous_y);
    previous_y = y;
    const double next_u = random.uniform(-1.0, 1.0);
    model.commit(next_u - u);
    u = next_u;
    plant.step(u);
  }
  // Noise-free and exactly representable, so the projection converges geometrically (measured
  // errors: 1e-3 / 1e-3 / 6e-2 after 1000 samples, 3e-8 / 5e-9 / 1.4e-7 after 5000, round-off
  // after 20000). The tolerances leave ~10-30x margin for another input sequence; a model that
  // cannot hold eq. 2 (d = 0, or L_y < 2) misses them by orders of magnitude.
  EXPECT_NEAR(model.a1(), 1.68125, 1e-6);
  EXPECT_NEAR(model.a2(), -0.68125, 1e-6);
  EXPECT_NEAR(model.b0(), 18.0, 1e-5);
}

TEST(FullFormDataModel, FreeResponseIsEquation2WithTheTrueParameters) {
  FullFormDataModelGains gains;
  gains.a1_initial = 1.68125;
  gains.a2_initial = -0.68125;
  gains.eta = 1e-9;  // (0, 1] required; effectively frozen
  FullFormDataModel model(gains);
  Equation2 plant;
  double u = 0.0, previous_y = 0.0;
  for (int k = 0; k < 50; ++k) {
    const double y = plant.y0;
    model.update(y - previous_y);
    previous_y = y;
    double next = 0.0, after = 0.0;
    model.free_response(y, 0.0, next, after);
    const double next_u = std::sin(0.3 * k);
    model.commit(next_u - u);
    // y(k+1) does not depend on u(k); y(k+2) does, with 18 um/V.
    Equation2 copy = plant;
    copy.step(u);  // u(k) = u(k-1): du(k) = 0
    EXPECT_NEAR(copy.y0, next, 1e-9) << k;
    EXPECT_NEAR(copy.y1, after, 1e-9) << k;
    u = next_u;
    plant.step(u);
  }
}

TEST(DataModelForm, ParsesCompactAndFullAndNamesTheFieldOtherwise) {
  EXPECT_EQ(parse_data_model_form("compact", "f"), DataModelForm::compact);
  EXPECT_EQ(parse_data_model_form("full", "f"), DataModelForm::full);
  try {
    parse_data_model_form("ffdl", "controller.mfac.data_model");
    FAIL() << "accepted 'ffdl'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("controller.mfac.data_model"), std::string::npos) << e.what();
  }
}

TEST(CoupledIncrements, WithoutANormalTheyAreThePerAxisLaws) {
  AxisPrediction x{IncrementRule::reaching_target, 2.0, 18.0, 1.5, 0.7, 20.0, 1.0, 0.0, -0.4};
  AxisPrediction y{IncrementRule::reaching_target, -1.0, 25.0, -0.5, -0.2, 20.0, 1.0, 0.0, 0.3};
  Eigen::Vector2d du = coupled_increments(x, y, Eigen::Vector2d::Zero());
  EXPECT_DOUBLE_EQ(du[0], DataDrivenAxisLaw::uncoupled_increment(x));
  EXPECT_DOUBLE_EQ(du[1], DataDrivenAxisLaw::uncoupled_increment(y));
  // With a normal, C4's increments put the coupled composite error on both targets.
  const Eigen::Vector2d n = Eigen::Vector2d(3.0, 4.0).normalized();
  du = coupled_increments(x, y, n);
  const Eigen::Vector2d tracking_next(x.free_error + x.gain * du[0], y.free_error + y.gain * du[1]);
  const Eigen::Vector2d tracking_now(x.tracking_error, y.tracking_error);
  const Eigen::Vector2d eps_next =
      Eigen::Vector2d(x.contour_error, y.contour_error) + n * n.dot(tracking_next - tracking_now);
  const Eigen::Vector2d composite = tracking_next + 20.0 * eps_next;
  EXPECT_NEAR(composite[0], x.target, 1e-12);
  EXPECT_NEAR(composite[1], y.target, 1e-12);
  x.rule = IncrementRule::least_squares;
  y.rule = IncrementRule::least_squares;
  x.rho = y.rho = 0.6;
  x.lambda = y.lambda = 0.1;
  du = coupled_increments(x, y, Eigen::Vector2d::Zero());
  EXPECT_DOUBLE_EQ(du[0], DataDrivenAxisLaw::uncoupled_increment(x));
  EXPECT_DOUBLE_EQ(du[1], DataDrivenAxisLaw::uncoupled_increment(y));
}

enum class Law { mfac, mfa_dtsmc };
enum class Plant { equation2, ballscrew };

struct CircleRun {
  bool diverged = false;
  double time_s = 0.0;  // of the divergence
  double rms_um = 0.0, max_um = 0.0;
};

// Paper 002's circle: R = 50 mm about (75, 75) mm, one revolution in 5 s from rest at (125, 75) mm,
// T = 1 ms, the paper's gains, the Steffensen foot point; diverged beyond 50 mm of contour error.
CircleRun run_circle(Law law, DataModelForm form, Plant plant_kind, ContourCoupling coupling, double duration_s) {
  const double h = 1e-3;
  CircleParameters circle;
  circle.center = Eigen::Vector2d(0.075, 0.075);
  circle.radius_m = 0.05;
  circle.period_s = 5.0;
  circle.revolutions = 2.0;  // netmc's assumption [A] for paper 002's circle
  auto trajectory = std::make_shared<CircleTrajectory>(circle);
  std::unique_ptr<DataDrivenAxisLaw> axes[2];
  for (auto& axis : axes) {
    if (law == Law::mfac) {
      CompactFormMfacGains gains;
      gains.data_model = form;
      axis = std::make_unique<CompactFormMfacAxis>(gains);
    } else {
      MfaDtsmcGains gains;
      gains.data_model = form;
      axis = std::make_unique<MfaDtsmcAxis>(gains, h);
    }
  }
  DataDrivenContouring controller(std::move(axes[0]), std::move(axes[1]),
                                  make_contour_error_estimator("steffensen", trajectory), h, 1e-6, coupling);
  const Eigen::Vector2d start = trajectory->sample(0.0).position;
  Equation2 discrete[2];
  plant::BallScrewDrive drives[2] = {plant::BallScrewDrive({}), plant::BallScrewDrive({})};
  for (int axis = 0; axis < 2; ++axis) {
    discrete[axis].reset(1e6 * start[axis]);
    drives[axis].reset(start[axis], 0.0);
  }
  const auto samples = static_cast<std::size_t>(std::lround(duration_s / h));
  controller.begin_iteration(start, samples);
  CircleRun out;
  double sum = 0.0;
  for (std::size_t k = 0; k < samples; ++k) {
    Eigen::Vector2d measured;
    for (int axis = 0; axis < 2; ++axis) {
      measured[axis] = plant_kind == Plant::equation2 ? 1e-6 * discrete[axis].y0 : drives[axis].position();
    }
    const double error_um = 1e6 * std::abs(trajectory->contour_error(measured));
    if (!std::isfinite(error_um) || error_um > 5e4) {
      out.diverged = true;
      out.time_s = static_cast<double>(k) * h;
      return out;
    }
    sum += error_um * error_um;
    out.max_um = std::max(out.max_um, error_um);
    ReferencePoint reference = trajectory->sample(static_cast<double>(k) * h);
    reference.time_s = static_cast<double>(k) * h;  // the foot-point search starts here
    const ContouringCycle cycle = controller.step(k, reference, measured);
    for (int axis = 0; axis < 2; ++axis) {
      if (plant_kind == Plant::equation2) {
        discrete[axis].step(cycle.command[axis]);
      } else {
        drives[axis].advance(h, cycle.command[axis]);
      }
    }
  }
  out.rms_um = std::sqrt(sum / static_cast<double>(samples));
  return out;
}

// With both fixes, on a plant that is exactly eq. 2, both laws hold the circle with the paper's
// gains. Measured: C3 RMS 0.025 um, max 0.69 um; C4 RMS 0.063 um, max 3.07 um (the first samples,
// from rest, dominate the max); bounds ~3-4x that.
TEST(DataDrivenContouring, FullFormWithCouplingIsStableOnEquation2) {
  const CircleRun c3 = run_circle(Law::mfac, DataModelForm::full, Plant::equation2, ContourCoupling::through_outputs, 10.0);
  ASSERT_FALSE(c3.diverged) << c3.time_s;
  EXPECT_LT(c3.rms_um, 0.1);
  EXPECT_LT(c3.max_um, 2.0);
  const CircleRun c4 =
      run_circle(Law::mfa_dtsmc, DataModelForm::full, Plant::equation2, ContourCoupling::through_outputs, 10.0);
  ASSERT_FALSE(c4.diverged) << c4.time_s;
  EXPECT_LT(c4.rms_um, 0.25);
  EXPECT_LT(c4.max_um, 10.0);
}

// Neither fix alone is enough on eq. 2: the compact form (paper 002's eq. 9) diverges with the
// coupling, and the full form with the per-axis eps(k+1) ~ eps(k) (measured: 8-15 ms).
TEST(DataDrivenContouring, EachFixAloneDivergesOnEquation2) {
  for (Law law : {Law::mfac, Law::mfa_dtsmc}) {
    const CircleRun compact =
        run_circle(law, DataModelForm::compact, Plant::equation2, ContourCoupling::through_outputs, 1.0);
    EXPECT_TRUE(compact.diverged);
    EXPECT_LT(compact.time_s, 0.1);
    const CircleRun frozen = run_circle(law, DataModelForm::full, Plant::equation2, ContourCoupling::frozen, 1.0);
    EXPECT_TRUE(frozen.diverged);
    EXPECT_LT(frozen.time_s, 0.1);
  }
}

// On the ballscrew plant (eq. 1 sampled exactly, as `--plant ballscrew`) the paper's compact form
// diverges within 20 ms whatever the coupling (docs/reproductions/paper-002.md, "Paper 002's data-driven controllers"). So
// does the full form: the exact sampled drive is (8.1 z + 7.3) / ((z - 1)(z - 0.727)) um/V, so
// u(k) already moves y(k+1), which the d = 1 model (exact for eq. 2 only) does not hold. These
// document the present limit; a data model that fixes it must change them and docs/status-and-limits.md.
TEST(DataDrivenContouring, BothFormsDivergeOnTheSampledBallscrew) {
  for (Law law : {Law::mfac, Law::mfa_dtsmc}) {
    for (DataModelForm form : {DataModelForm::compact, DataModelForm::full}) {
      for (ContourCoupling coupling : {ContourCoupling::through_outputs, ContourCoupling::frozen}) {
        const CircleRun run = run_circle(law, form, Plant::ballscrew, coupling, 1.0);
        EXPECT_TRUE(run.diverged) << data_model_form_name(form);
        EXPECT_LT(run.time_s, 0.05) << data_model_form_name(form);
      }
    }
  }
}

}  // namespace
}  // namespace netmc::control
