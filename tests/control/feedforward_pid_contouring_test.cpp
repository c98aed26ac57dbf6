// Paper 004 in the time domain: the per-axis loop of eq. 2 with feedforward against the
// continuous closed loop of the frequency library, the feedforward term, the cross-coupling laws
// of eq. 13 and eq. 20 against their Tustin difference equations expanded by hand, and the
// distribution of the coupling command (paper 004, eq. 6, with the signs of paper 001's eq. 15).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "control/axis/feedforward_pid_axis.hpp"
#include "control/cross_coupling/tustin_cross_coupling.hpp"
#include "control/cross_coupling/feedforward_pid_contouring.hpp"
#include "control/cross_coupling/tustin_cross_coupling.hpp"
#include "control/frequency/qft_bounds.hpp"
#include "control/trajectory/circle_trajectory.hpp"
#include "plant/resonant_stage_axis.hpp"

namespace netmc::control {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLoopPeriodS = 5e-5;  // 20 kHz, netmc's choice [A]

plant::ResonantStageParameters x_stage() {
  plant::ResonantStageParameters p;
  p.mass = 24.0;
  p.modes = {{0.013, 0.040, 150.0}, {0.0023, 0.018, 292.0}, {0.0018, 0.027, 510.0}};  // Table 1
  return p;
}

// Steady-state tracking error of the sampled loop (stage004's X axis, force held over each
// period) for r = A sin(w t), as a phasor E/R from the last whole periods.
std::complex<double> sampled_error_ratio(double frequency_hz) {
  FeedforwardPidAxis axis(paper004_x_axis_gains(), kLoopPeriodS);
  plant::ResonantStageAxis stage(x_stage());
  stage.reset(0.0, 0.0);
  const double w = 2 * kPi * frequency_hz, amplitude = 1e-3;
  const int samples = static_cast<int>(std::round(3.0 / kLoopPeriodS));
  const int window = static_cast<int>(std::round(1.0 / kLoopPeriodS));  // 1 s: whole periods of a whole Hz
  std::complex<double> projection = 0.0;
  for (int k = 0; k < samples; ++k) {
    const double t = k * kLoopPeriodS;
    // Starts at rest: r = A sin(w t) has r(0) = 0 but r'(0) != 0; the transient has died out
    // long before the window (the slowest closed-loop pole is near the integral corner, 5.6 Hz).
    const double reference = amplitude * std::sin(w * t);
    const double error = reference - stage.position();
    const double force = axis.step(reference, -w * w * reference, stage.position());
    if (k >= samples - window) projection += error * std::exp(std::complex<double>(0.0, -w * t));
    stage.advance(kLoopPeriodS, force);
  }
  // E(t) = |E| sin(w t + arg E): its projection on e^{-jwt} over whole periods is N |E| e^{j(arg E - pi/2)}/2.
  return 2.0 * projection / static_cast<double>(window) * std::complex<double>(0.0, 1.0) / amplitude;
}

// The continuous loop (frequency library): E/R = (1 - G_f P D)/(1 + G_c P D), G_f = 0.85 m s^2,
// with the hold of the sampled loop as half a period of delay, D = e^{-sT/2} (1 without it).
std::complex<double> continuous_error_ratio(double frequency_hz, bool with_hold_delay) {
  const double w = 2 * kPi * frequency_hz;
  const std::complex<double> s(0.0, w);
  const std::complex<double> p = stage_axis_plant(paper004_x_axis()).at(w);
  const std::complex<double> gc = feedforward_pid_feedback(paper004_x_axis_gains()).at(w);
  const std::complex<double> hold = with_hold_delay ? std::exp(-s * (kLoopPeriodS / 2)) : 1.0;
  return (1.0 - 0.85 * 24.0 * s * s * p * hold) / (1.0 + gc * p * hold);
}

TEST(FeedforwardPidAxis, SampledLoopTracksASineAsTheContinuousClosedLoop) {
  // Against the continuous loop with the hold's half-period delay the sampled loop agrees to
  // 0.1 % and 1 mrad (Tustin's warping of G_c is 5e-6 at 40 Hz). The delay itself moves E/R by
  // 0.8 % and 37 mrad at 40 Hz, where |S| = 1.23 amplifies it, and by 5 mrad at 5 Hz.
  for (const double f : {5.0, 40.0}) {
    const std::complex<double> sampled = sampled_error_ratio(f), continuous = continuous_error_ratio(f, true);
    EXPECT_NEAR(std::abs(sampled) / std::abs(continuous), 1.0, 1e-3) << f << " Hz: " << sampled << " vs " << continuous;
    EXPECT_NEAR(std::arg(sampled / continuous), 0.0, 1e-3) << f << " Hz";
    const std::complex<double> undelayed = continuous_error_ratio(f, false);
    EXPECT_NEAR(std::abs(sampled) / std::abs(undelayed), 1.0, 0.01) << f << " Hz";
    EXPECT_NEAR(std::arg(sampled / undelayed), 0.0, 0.04) << f << " Hz";
  }
  // The feedforward matters: without it the error at 5 Hz would be 1/0.15 times larger.
  EXPECT_LT(std::abs(continuous_error_ratio(5.0, false)), 0.01);
}

TEST(FeedforwardPidAxis, FeedbackIsTheTustinMapOfEq2) {
  const FeedforwardPidGains y = paper004_y_axis_gains();
  EXPECT_EQ(y.mass_kg, 30.0);
  FeedforwardPidAxis axis(y, kLoopPeriodS);
  // paper 004, eq. 2 with K_p = m (2 pi f_bw)^2 / alpha: the low-frequency asymptote K_p w_i / s.
  const double kp = 30.0 * std::pow(2 * kPi * 50.0, 2) / 3.0, wi = 2 * kPi * 50.0 / 9.0;
  EXPECT_NEAR(std::abs(axis.continuous_feedback().at(1e-3)) * 1e-3 / (kp * wi), 1.0, 1e-6);
  // The bilinear map: H(e^{jwT}) = G_c(j (2/T) tan(wT/2)) exactly.
  for (const double f : {1.0, 50.0, 150.0, 2000.0}) {
    const double w = 2 * kPi * f;
    const std::complex<double> h = axis.discrete_feedback().at(w);
    const std::complex<double> g = axis.continuous_feedback().at(2.0 / kLoopPeriodS * std::tan(w * kLoopPeriodS / 2));
    EXPECT_NEAR(std::abs(h / g - 1.0), 0.0, 1e-9) << f << " Hz";
  }
}

TEST(FeedforwardPidAxis, FeedforwardIsExactlyEightyFivePercentOfMassTimesAcceleration) {
  FeedforwardPidAxis axis(paper004_x_axis_gains(), kLoopPeriodS);
  for (const double acceleration : {0.0, 0.63, -2.5, 1e-7}) {
    EXPECT_EQ(axis.feedforward(acceleration), 0.85 * 24.0 * acceleration);
    // With no tracking error the feedback filter stays at rest: u is the feedforward alone.
    EXPECT_EQ(axis.step(0.01, acceleration, 0.01), 0.85 * 24.0 * acceleration);
  }
  FeedforwardPidGains none = paper004_x_axis_gains();
  none.feedforward_fraction = 0.0;
  EXPECT_EQ(FeedforwardPidAxis(none, kLoopPeriodS).feedforward(3.0), 0.0);
}

TEST(FeedforwardPidAxis, RefusesBadGainsNamingThem) {
  const auto error_of = [](FeedforwardPidGains gains, double period = kLoopPeriodS) -> std::string {
    try {
      FeedforwardPidAxis axis(gains, period);
    } catch (const std::invalid_argument& error) {
      return error.what();
    }
    return "";
  };
  FeedforwardPidGains g = paper004_x_axis_gains();
  g.mass_kg = -1.0;
  EXPECT_NE(error_of(g).find("ffpid mass_kg"), std::string::npos);
  g = paper004_x_axis_gains();
  g.alpha = 0.0;
  EXPECT_NE(error_of(g).find("ffpid alpha"), std::string::npos);
  g = paper004_x_axis_gains();
  g.feedforward_fraction = std::nan("");
  EXPECT_NE(error_of(g).find("ffpid feedforward_fraction"), std::string::npos);
  // f_lp = alpha f_bw = 150 Hz is above the Nyquist frequency of a 5 ms loop (100 Hz).
  EXPECT_NE(error_of(paper004_x_axis_gains(), 0.005).find("Nyquist"), std::string::npos);
}

// Polynomials in q = z^-1, lowest power first.
using Poly = std::vector<double>;
Poly times(const Poly& a, const Poly& b) {
  Poly c(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}
Poly plus(Poly a, const Poly& b) {
  if (a.size() < b.size()) a.resize(b.size(), 0.0);
  for (std::size_t i = 0; i < b.size(); ++i) a[i] += b[i];
  return a;
}
Poly scaled(Poly a, double k) {
  for (double& c : a) c *= k;
  return a;
}

// Runs y(k) = (sum b_i u(k-i) - sum_{i>0} a_i y(k-i)) / a_0 (direct form I) next to the
// compensator and returns the largest relative difference.
double worst_difference_from(const Poly& b, const Poly& a, ContourCompensator& compensator) {
  std::vector<double> u, y;
  double worst = 0.0, scale = 0.0;
  compensator.begin_iteration(0);
  for (int k = 0; k < 4000; ++k) {
    u.push_back(1e-6 * (std::sin(0.013 * k) + (k == 0 ? 1.0 : 0.0) + (k % 97 == 0 ? 0.5 : 0.0)));
    double value = 0.0;
    for (std::size_t i = 0; i < b.size() && i <= static_cast<std::size_t>(k); ++i) value += b[i] * u[k - i];
    for (std::size_t i = 1; i < a.size() && i <= static_cast<std::size_t>(k); ++i) value -= a[i] * y[k - i];
    y.push_back(value / a[0]);
    const double output = compensator.command(static_cast<std::size_t>(k), u.back());
    scale = std::max(scale, std::abs(y.back()));
    worst = std::max(worst, std::abs(output - y.back()));
  }
  return worst / scale;
}

TEST(TustinCrossCoupling, PidTypeLawOfEq13IsItsTustinDifferenceEquation) {
  // s = c (1 - q)/(1 + q), c = 2/T; both sides of eq. 13 times (1 + q)^3.
  const FilteredPidCrossCouplingGains g;  // Table 3
  EXPECT_EQ(g.kp, 5e5);
  EXPECT_EQ(g.ki, 1e8);
  EXPECT_EQ(g.kd, 3.0);
  const double c = 2.0 / kLoopPeriodS, w = 2 * kPi * g.low_pass_hz, z = g.low_pass_damping;
  const Poly minus{1.0, -1.0}, sum{1.0, 1.0};
  const Poly b = scaled(plus(plus(scaled(times(times(minus, minus), sum), g.kd * c * c),
                                  scaled(times(minus, times(sum, sum)), g.kp * c)),
                             scaled(times(sum, times(sum, sum)), g.ki)),
                        w * w);
  const Poly a = scaled(times(minus, plus(plus(scaled(times(minus, minus), c * c), scaled(times(minus, sum), 2 * z * w * c)),
                                          scaled(times(sum, sum), w * w))),
                        c);
  TustinCrossCoupling law = make_low_pass_pid_cross_coupling(g, kLoopPeriodS);
  EXPECT_LT(worst_difference_from(b, a, law), 1e-9);
  EXPECT_NE(law.describe().find("lpccc"), std::string::npos);
}

TEST(TustinCrossCoupling, QftLawOfEq20IsItsTustinDifferenceEquation) {
  // C(s) = K (s + p)^2 / (s (s + r)^2): each factor maps on its own, times (1 + q)^3.
  const double k = 2.75e11, p = 374.4, r = 11230.0, c = 2.0 / kLoopPeriodS;
  const Poly zero{c + p, -(c - p)}, pole{c + r, -(c - r)};
  const Poly b = scaled(times(Poly{1.0, 1.0}, times(zero, zero)), k);
  const Poly a = scaled(times(Poly{1.0, -1.0}, times(pole, pole)), c);
  TustinCrossCoupling law = make_qft_cross_coupling(kLoopPeriodS);
  EXPECT_LT(worst_difference_from(b, a, law), 1e-9);
  // The clone runs the same law from rest.
  auto copy = law.clone();
  EXPECT_LT(worst_difference_from(b, a, *copy), 1e-9);
}

// Paper 004's uncoupled loops (Tables 1 and 2) with `compensator` (none: uncoupled) and the
// tangent estimator of its eq. 3.
std::unique_ptr<FeedforwardPidContouring> paper004_controller(std::unique_ptr<ContourCompensator> compensator) {
  if (!compensator) compensator = std::make_unique<NoContourCompensation>();
  return std::make_unique<FeedforwardPidContouring>(paper004_x_axis_gains(), paper004_y_axis_gains(), kLoopPeriodS,
                                                    make_contour_error_estimator("tangent"), std::move(compensator));
}

TEST(FeedforwardPidContouring, DistributesTheCouplingCommandAsEq6) {
  // At angle 0 of a counter-clockwise circle the tangent is +y: C_x = sin(phi) = 1, C_y = 0.
  CircleTrajectory circle({{0.0, 0.0}, 0.05, 2.0});
  const ReferencePoint reference = circle.sample(0.0);
  const Eigen::Vector2d measured = reference.position + Eigen::Vector2d(2e-6, 1e-6);  // outside
  auto uncoupled = paper004_controller(nullptr);
  auto coupled = paper004_controller(std::make_unique<TustinCrossCoupling>(make_qft_cross_coupling(kLoopPeriodS)));
  uncoupled->begin_iteration(reference.position, 10);
  coupled->begin_iteration(reference.position, 10);
  const ContouringCycle u = uncoupled->step(0, reference, measured);
  const ContouringCycle U = coupled->step(0, reference, measured);
  // eq. 3: eps_c = E_y cos(phi) - E_x sin(phi) with E = r - y = (-2, -1) um: +2 um (outside).
  EXPECT_NEAR(U.estimate.contour_error, 2e-6, 1e-15);
  EXPECT_NEAR(U.estimate.cx, 1.0, 1e-12);
  EXPECT_NEAR(U.estimate.cy, 0.0, 1e-12);
  // The per-axis commands do not see the coupling.
  EXPECT_EQ(U.axis_command, u.axis_command);
  EXPECT_EQ(u.coupling_command, 0.0);
  // From rest the Tustin filter's first output is b_0 eps_c.
  const double first_output =
      make_qft_cross_coupling(kLoopPeriodS).discrete_law().numerator[0] * U.estimate.contour_error;
  EXPECT_DOUBLE_EQ(U.coupling_command, first_output);
  EXPECT_GT(U.coupling_command, 0.0);
  // U_x = u_x - C_x u_c pushes the outside point back towards the centre (-x); U_y = u_y.
  EXPECT_NEAR(U.command.x(), U.axis_command.x() - U.coupling_command, 1e-9);
  EXPECT_EQ(U.command.y(), U.axis_command.y());
  EXPECT_LT(U.command.x(), u.command.x());
  EXPECT_NE(coupled->describe().find("qftccc"), std::string::npos);
  EXPECT_NE(coupled->describe().find("m=30 kg"), std::string::npos);
}

TEST(FeedforwardPidContouring, AtRestTheTangentIsTheLastDirectionOfTravel) {
  // The ramped circle ends at rest at (R, 0), where it arrived travelling +y.
  CircleParameters p;
  p.radius_m = 0.05;
  p.period_s = 2.0;
  p.ramp_s = 0.2;
  const CircleTrajectory circle(p);
  auto controller = paper004_controller(std::make_unique<TustinCrossCoupling>(make_qft_cross_coupling(kLoopPeriodS)));
  controller->begin_iteration(circle.sample(0.0).position, 10);
  const Eigen::Vector2d offset(1e-6, 0.0);  // outside the circle at (R, 0)
  // Before any travel the estimator's own fallback applies (+x: C_x = 0).
  EXPECT_NEAR(controller->step(0, circle.sample(0.0), circle.sample(0.0).position + offset).estimate.cx, 0.0, 1e-12);
  controller->step(1, circle.sample(1.99), circle.sample(1.99).position);
  const ReferencePoint stopped = circle.sample(2.2);
  ASSERT_EQ(stopped.velocity.norm(), 0.0);
  const ContouringCycle held = controller->step(2, stopped, stopped.position + offset);
  EXPECT_NEAR(held.estimate.cx, 1.0, 1e-6);  // sin(phi), phi = 90 degrees
  EXPECT_NEAR(held.estimate.cy, 0.0, 1e-3);
  EXPECT_NEAR(held.estimate.contour_error, 1e-6, 1e-11);  // the true contour error
  // A new iteration forgets the direction.
  controller->begin_iteration(circle.sample(0.0).position, 10);
  EXPECT_NEAR(controller->step(0, stopped, stopped.position + offset).estimate.cx, 0.0, 1e-12);
}

}  // namespace
}  // namespace netmc::control
