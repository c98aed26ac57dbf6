// TD, ESO and ADRC against closed forms and an independent integration.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/axis/adrc_controller.hpp"

namespace netmc::control {
namespace {

TEST(TrackingDifferentiator, ConvergesToAStepWithoutOvershoot) {
  TrackingDifferentiator td(160.0, 0.005);  // r0*h = 0.8: discrete poles at 0.2 (critically damped)
  td.reset(0.0);
  double peak = 0.0;
  for (int k = 0; k < 200; ++k) {
    td.update(1.0);
    peak = std::max(peak, td.position());
  }
  EXPECT_NEAR(td.position(), 1.0, 1e-12);
  EXPECT_NEAR(td.velocity(), 0.0, 1e-12);
  EXPECT_LE(peak, 1.0 + 1e-12);
}

TEST(TrackingDifferentiator, VelocityOfARampIsExactInSteadyState) {
  const double h = 0.005;
  TrackingDifferentiator td(160.0, h);
  td.reset(0.0);
  const double slope = 0.02;  // m/s
  for (int k = 0; k < 400; ++k) td.update(slope * k * h);
  EXPECT_NEAR(td.velocity(), slope, 1e-10);
  // Steady state of eq. 8 with v2 = slope: v1(k) - v0(k) = -2 slope / r0, as for the continuous
  // filter.
  EXPECT_NEAR(slope * 400 * h - td.position(), 2.0 * slope / 160.0, 1e-12);
}

TEST(TrackingDifferentiator, SineGainMatchesContinuousTransferFunctionForSmallSteps) {
  // v1 = r0^2/(s+r0)^2 v0: gain r0^2/(r0^2 + w^2) at frequency w.
  const double r0 = 50.0, w = 30.0, h = 1e-5;
  TrackingDifferentiator td(r0, h);
  td.reset(0.0);
  double peak = 0.0;
  const int steps = static_cast<int>(2.0 / h);
  for (int k = 0; k < steps; ++k) {
    td.update(std::sin(w * k * h));
    if (k * h > 1.0) peak = std::max(peak, std::abs(td.position()));
  }
  EXPECT_NEAR(peak, r0 * r0 / (r0 * r0 + w * w), 2e-3);
}

// Exact double integrator with input gain b and constant disturbance d.
struct DoubleIntegrator {
  double b, d, x = 0.0, v = 0.0;
  void advance(double h, double u) {
    const double a = b * u + d;
    x += v * h + 0.5 * a * h * h;
    v += a * h;
  }
};

class ObserverTest : public ::testing::TestWithParam<Discretization> {};

TEST_P(ObserverTest, EstimatesAConstantDisturbance) {
  // The axis is held at rest by u = -d/b: the total disturbance is d (b0 = b, no other dynamics).
  const double h = 0.005, b = 20.0, d = -0.7;
  ExtendedStateObserver observer(100.0, b, h, GetParam());
  observer.reset(0.0);
  for (int k = 0; k < 400; ++k) observer.update(0.0, -d / b);
  EXPECT_NEAR(observer.disturbance(), d, 1e-9);
  EXPECT_NEAR(observer.velocity(), 0.0, 1e-9);
}

TEST_P(ObserverTest, IsExactOnACoastingAxis) {
  // A kick, then u cancels d and the axis coasts at constant velocity.
  const double h = 0.005, b = 20.0, d = -0.7;
  ExtendedStateObserver observer(100.0, b, h, GetParam());
  observer.reset(0.0);
  DoubleIntegrator plant{b, d};
  for (int k = 0; k < 1000; ++k) {
    const double u = k < 20 ? 0.05 : -d / b;
    observer.update(plant.x, u);
    plant.advance(h, u);
  }
  EXPECT_NEAR(observer.velocity(), plant.v, 1e-9);
  EXPECT_NEAR(observer.disturbance(), d, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(BothDiscretizations, ObserverTest,
                         ::testing::Values(Discretization::forward_euler,
                                           Discretization::zero_order_hold));

// The observer error from any initial state obeys the difference equation of (lambda - p)^3:
// p = 1 - w0 h for eq. 9 (Euler), p = exp(-w0 h) for the exact discretization.
void expect_triple_pole(Discretization discretization, double p) {
  const double w0 = 100.0, h = 0.005;
  ExtendedStateObserver observer(w0, 20.0, h, discretization);
  observer.reset(1.0, -2.0, 30.0);
  std::vector<Eigen::Vector3d> z{{observer.position(), observer.velocity(), observer.disturbance()}};
  for (int k = 0; k < 6; ++k) {
    observer.update(0.0, 0.0);
    z.emplace_back(observer.position(), observer.velocity(), observer.disturbance());
  }
  for (std::size_t k = 3; k < z.size(); ++k) {
    const Eigen::Vector3d residual =
        z[k] - 3 * p * z[k - 1] + 3 * p * p * z[k - 2] - p * p * p * z[k - 3];
    EXPECT_LT(residual.norm(), 1e-9 * (1.0 + z[0].norm()));
  }
}

TEST(ExtendedStateObserver, EulerErrorDynamicsHaveTripleEigenvalueOneMinusW0H) {
  expect_triple_pole(Discretization::forward_euler, 1.0 - 100.0 * 0.005);
}

TEST(ExtendedStateObserver, ExactDiscretizationHasTripleEigenvalueExpMinusW0H) {
  expect_triple_pole(Discretization::zero_order_hold, std::exp(-100.0 * 0.005));
}

TEST(ExtendedStateObserver, ExactDiscretizationTracksAnAcceleratingAxisWithoutBias) {
  // u = 0 and a constant disturbance: the axis accelerates. The exact model has no truncation
  // error, so its estimates converge to the true state; Euler's position model x + h v misses
  // the h^2 a / 2 term and keeps a bias.
  const double h = 0.005, b = 20.0, d = 0.4;
  ExtendedStateObserver euler(100.0, b, h), exact(100.0, b, h, Discretization::zero_order_hold);
  euler.reset(0.0);
  exact.reset(0.0);
  DoubleIntegrator plant{b, d};
  for (int k = 0; k < 400; ++k) {
    euler.update(plant.x, 0.0);
    exact.update(plant.x, 0.0);
    plant.advance(h, 0.0);
  }
  // Both predict the state of the next sample from y(k): compare with the plant now.
  EXPECT_NEAR(exact.disturbance(), d, 1e-9);
  EXPECT_NEAR(exact.velocity(), plant.v, 1e-9);
  EXPECT_NEAR(exact.position(), plant.x, 1e-9);
  EXPECT_GT(std::abs(euler.velocity() - plant.v), 1e-4);
}

TEST(ExtendedStateObserver, RejectsNonPositiveBandwidth) {
  EXPECT_THROW(ExtendedStateObserver(0.0, 20.0, 0.005), std::invalid_argument);
  EXPECT_THROW(ExtendedStateObserver(100.0, std::nan(""), 0.005), std::invalid_argument);
}

// Closed loop on x'' = -20 x' + 20 u + d tracking a ramp; returns the final tracking error and
// the observer's total-disturbance estimate.
// Gains with a stiffer position loop than paper 001's (whose slow mode, kp*b0 = 1.6 against
// kd*b0 = 120, takes minutes to settle): closed loop s^2 + 20 s + 400.
std::pair<double, double> track_ramp_with_adrc(double d) {
  const double h = 0.005, slope = 0.01;
  AdrcGains gains;
  gains.kp = 20.0;
  gains.kd = 1.0;
  AdrcController adrc(gains, h);
  adrc.reset(0.0);
  double x = 0.0, v = 0.0, error = 0.0;
  for (int k = 0; k <= 4000; ++k) {
    const double reference = slope * k * h;
    const double u = adrc.command(reference, x);
    adrc.commit(reference, x, u, u);
    error = reference - x;
    for (int i = 0; i < 50; ++i) {  // midpoint rule, fine steps over the period
      const double dt = h / 50;
      const double vm = v + 0.5 * dt * (-20 * v + 20 * u + d);
      x += dt * vm;
      v += dt * (-20 * vm + 20 * u + d);
    }
  }
  return {error, adrc.observer().disturbance()};
}

TEST(AdrcController, RejectsAConstantDisturbanceWhileTrackingARamp) {
  const auto [error_without, estimate_without] = track_ramp_with_adrc(0.0);
  const auto [error_with, estimate_with] = track_ramp_with_adrc(0.3);
  // The observer takes the disturbance: the steady tracking error does not depend on it...
  EXPECT_NEAR(error_with, error_without, 1e-8);
  // ...and it is the lag of the TD and observer on a 10 mm/s ramp, well under 1 mm.
  // ...and what remains is the lag of the tracking differentiator, 2*slope/r0 (see above): the
  // loop follows v1 exactly.
  EXPECT_NEAR(error_without, 2.0 * 0.01 / 160.0, 1e-8);
  // Total disturbance on the ramp: a2*x' + d = -20*slope + d.
  EXPECT_NEAR(estimate_without, -20 * 0.01, 1e-6);
  EXPECT_NEAR(estimate_with, -20 * 0.01 + 0.3, 1e-6);
}

}  // namespace
}  // namespace netmc::control
