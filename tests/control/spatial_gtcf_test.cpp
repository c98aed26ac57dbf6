// Three-axis GTCF (thesis ch. 6) on a circle in space: the task coordinates against the exact
// distance to the circle and against finite differences, and SARC closing the loop of three
// linear-motor axes (friction and cogging unknown to the controller, 0.5 um encoder).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/trajectory/spatial_circle.hpp"
#include "control/task_space/spatial_sarc.hpp"
#include "plant/plant_catalog.hpp"
#include "plant/position_sensor.hpp"

namespace netmc::control {
namespace {

SpatialCircleParameters tilted_circle() {
  SpatialCircleParameters p;
  p.center = {0.10, 0.10, 0.05};
  p.radius_m = 0.05;
  p.normal = {-1.0, 1.0, 0.5};
  p.start = {0.0, 0.0, 1.0};
  p.period_s = 2.0 * std::numbers::pi / 4.0;  // 4 rad/s: 0.2 m/s
  return p;
}

TEST(SpatialCircle, JacobianIsOrthonormalOnTheContourAndRmIsArcLength) {
  const SpatialCircle circle(tilted_circle());
  for (double t : {0.0, 0.3, 0.7, 1.1, 1.5}) {
    const auto on = circle.sample(t);
    const auto r = circle.at(on.position);
    EXPECT_NEAR(r.r[0], 0.0, 1e-15);
    EXPECT_NEAR(r.r[1], 0.0, 1e-15);
    EXPECT_NEAR(std::remainder(r.r[2] - 0.2 * t, circle.perimeter_m()), 0.0, 1e-12) << t;
    EXPECT_TRUE((r.jacobian * r.jacobian.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-12)) << t;
    // grad rm is the unit tangent along the motion.
    EXPECT_TRUE(r.jacobian.row(2).transpose().isApprox(on.velocity.normalized(), 1e-12)) << t;
  }
}

TEST(SpatialCircle, JacobianEqualsFiniteDifferencesOffTheContour) {
  const SpatialCircle circle(tilted_circle());
  const Eigen::Vector3d q = circle.sample(0.4).position + Eigen::Vector3d(0.003, -0.002, 0.004);
  const auto r = circle.at(q);
  const double step = 1e-7;
  for (int j = 0; j < 3; ++j) {
    Eigen::Vector3d dq = Eigen::Vector3d::Zero();
    dq[j] = step;
    const Eigen::Vector3d column = (circle.at(q + dq).r - circle.at(q - dq).r) / (2.0 * step);
    EXPECT_TRUE(column.isApprox(r.jacobian.col(j), 1e-6)) << j;
  }
}

TEST(SpatialCircle, ContourCoordinatesAreTheExactDistanceToFirstOrder) {
  const SpatialCircle circle(tilted_circle());
  const auto on = circle.sample(0.9);
  const auto frame = circle.at(on.position);
  // Off the contour along a mix of both contour normals and the tangent.
  const Eigen::Vector3d direction = (0.6 * frame.jacobian.row(0) + 0.8 * frame.jacobian.row(1) +
                                     0.5 * frame.jacobian.row(2)).transpose();
  double previous = 0.0;
  for (double offset : {4e-3, 2e-3, 1e-3, 0.5e-3}) {
    const Eigen::Vector3d q = on.position + offset * direction;
    const double gap = std::abs(circle.at(q).r.head<2>().norm() - circle.distance(q));
    EXPECT_LT(gap, 0.05 * circle.distance(q)) << offset;
    if (previous > 0.0) {
      EXPECT_GT(previous / gap, 3.5) << offset;  // quadratic: 4x per halving
    }
    previous = gap;
  }
}

TEST(SpatialCircle, RejectsDegenerateParameters) {
  SpatialCircleParameters p = tilted_circle();
  p.normal = Eigen::Vector3d::Zero();
  EXPECT_THROW(SpatialCircle{p}, std::invalid_argument);
  p = tilted_circle();
  p.start = p.normal;
  EXPECT_THROW(SpatialCircle{p}, std::invalid_argument);
  p = tilted_circle();
  p.radius_m = 0.0;
  EXPECT_THROW(SpatialCircle{p}, std::invalid_argument);
  const SpatialCircle circle(tilted_circle());
  EXPECT_THROW(circle.at(tilted_circle().center), std::invalid_argument);
}

struct LoopResult {
  double steady_rms_m = 0.0, steady_max_m = 0.0, max_command = 0.0;
};

// Virtual time: sample, compute, hold the command for one period (no network).
LoopResult run_three_axis_loop(double duration_s) {
  const double h = 2e-4;
  auto contour = std::make_shared<SpatialCircle>(tilted_circle());
  SpatialSarc controller(SpatialSarcGains{}, h, contour);
  auto plants = plant::make_plant_set("linmotor", 3);
  plant::PositionSensor sensor({.resolution_m = 0.5e-6}, 1, 0);
  const Eigen::Vector3d start = contour->sample(0.0).position;
  for (int i = 0; i < 3; ++i) plants.axes[i]->reset(start[i], 0.0);
  controller.begin(start);
  LoopResult out;
  double squares = 0.0;
  long steady = 0;
  const long cycles = std::lround(duration_s / h);
  for (long k = 0; k < cycles; ++k) {
    const double t = static_cast<double>(k) * h;
    Eigen::Vector3d measured, truth;
    for (int i = 0; i < 3; ++i) {
      truth[i] = plants.axes[i]->position();
      measured[i] = sensor.measure(truth[i]);
    }
    if (t >= 2.0 * tilted_circle().period_s) {  // after two revolutions, as the thesis judges
      const double e = contour->distance(truth);
      squares += e * e;
      ++steady;
      out.steady_max_m = std::max(out.steady_max_m, e);
    }
    const Eigen::Vector3d u = controller.step(contour->sample(t), measured);
    out.max_command = std::max(out.max_command, u.cwiseAbs().maxCoeff());
    for (int i = 0; i < 3; ++i) plants.axes[i]->advance(h, u[i]);
  }
  out.steady_rms_m = std::sqrt(squares / static_cast<double>(std::max(steady, 1L)));
  return out;
}

TEST(SpatialSarc, ContoursACircleInSpaceWithThreeLinearMotorAxes) {
  const LoopResult result = run_three_axis_loop(4.0);
  EXPECT_TRUE(std::isfinite(result.steady_rms_m));
  EXPECT_LT(result.steady_rms_m, 3e-6);
  EXPECT_LT(result.steady_max_m, 10e-6);
  EXPECT_LT(result.max_command, 50.0);
  std::printf("three-axis GTCF-SARC: steady RMS %.3f um, max %.3f um, max |u| %.2f V\n",
              result.steady_rms_m * 1e6, result.steady_max_m * 1e6, result.max_command);
}

}  // namespace
}  // namespace netmc::control
