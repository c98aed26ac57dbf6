// In-loop foot-point contour-error estimators (paper 002, sec. 4) against the exact signed
// contour error, on the circle (closed form) and the heart (global search).

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "control/contour_error/contour_error_estimator.hpp"
#include "control/trajectory/foot_point.hpp"
#include "control/trajectory/circle_trajectory.hpp"
#include "control/trajectory/heart_trajectory.hpp"
#include "netsim/random_stream.hpp"

namespace netmc::control {
namespace {

// `orientation`: +1 for a counter-clockwise contour, -1 for a clockwise one. The estimators sign
// the error positive on the right of travel, the metric positive outside.
void expect_matches_exact(const std::shared_ptr<const ReferenceTrajectory>& trajectory, const char* name,
                          double orientation) {
  const auto estimator = make_contour_error_estimator(name, trajectory);
  EXPECT_EQ(estimator->name(), name);
  netsim::RandomStream random(3);
  const double duration = trajectory->duration_s();
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const double t = duration * (0.02 + 0.45 * random.uniform());  // away from the heart's cusps
    ReferencePoint reference = trajectory->sample(t);
    reference.time_s = t;
    // A point lagging 0-5 ms along the path and 0-100 um off it.
    const ReferencePoint lagging = trajectory->sample(t - 0.005 * random.uniform());
    const Eigen::Vector2d normal = Eigen::Vector2d(lagging.velocity.y(), -lagging.velocity.x()).normalized();
    const Eigen::Vector2d point = lagging.position + random.uniform(-1e-4, 1e-4) * normal;
    const ContourErrorEstimate e = estimator->estimate(reference, point);
    EXPECT_NEAR(e.contour_error, orientation * trajectory->contour_error(point), 1e-9) << name << " at t = " << t;
    // (cx, -cy) is the unit normal and eps (cx, -cy) the error vector P - C(t*).
    EXPECT_NEAR(std::hypot(e.cx, e.cy), 1.0, 1e-12);
    EXPECT_NEAR(contour_error_vector(e).norm(), std::abs(trajectory->contour_error(point)), 1e-9);
    EXPECT_GT(e.iterations, 0);
    ++checked;
  }
  EXPECT_EQ(checked, 400);
}

TEST(FootPointEstimator, NewtonAndSteffensenMatchTheExactErrorOnTheCircle) {
  CircleParameters p;
  p.center = {0.075, 0.075};
  p.radius_m = 0.05;
  p.period_s = 5.0;
  const auto circle = std::make_shared<CircleTrajectory>(p);
  expect_matches_exact(circle, "newton", 1.0);
  expect_matches_exact(circle, "steffensen", 1.0);
}

TEST(FootPointEstimator, NewtonAndSteffensenMatchTheExactErrorOnTheHeart) {
  const auto heart = std::make_shared<HeartTrajectory>(HeartParameters{});
  // The heart is traced clockwise (x grows from the top cusp).
  expect_matches_exact(heart, "newton", -1.0);
  expect_matches_exact(heart, "steffensen", -1.0);
}

TEST(FootPointEstimator, NeedsTheTrajectoryAndANameItKnows) {
  EXPECT_THROW(make_contour_error_estimator("steffensen"), std::invalid_argument);
  try {
    make_contour_error_estimator("secant");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tangent, curvature, newton, steffensen"), std::string::npos);
  }
}

}  // namespace
}  // namespace netmc::control

namespace netmc::control {
namespace {

// The cost model `netmc cee` states: Newton one curve evaluation per iteration, Steffensen two
// per full iteration and one for the last; both return the evaluation they stopped at.
TEST(FootPointCost, EvaluationsFollowTheIterations) {
  const HeartTrajectory heart{HeartParameters{}};
  netsim::RandomStream random(5);
  for (int i = 0; i < 200; ++i) {
    const double t = 0.2 + 4.5 * random.uniform();
    const auto lagging = heart.sample(t - 0.01);
    const Eigen::Vector2d point = lagging.position + Eigen::Vector2d(3e-5, -2e-5);
    const FootPoint newton = newton_foot_point(heart, point, t);
    EXPECT_EQ(newton.evaluations, newton.iterations);
    const FootPoint steffensen = steffensen_foot_point(heart, point, t);
    EXPECT_GE(steffensen.evaluations, steffensen.iterations);
    EXPECT_LE(steffensen.evaluations, 2 * steffensen.iterations);
    // The position returned is C at the returned time, and the distance is to it.
    for (const FootPoint& f : {newton, steffensen}) {
      EXPECT_NEAR((heart.sample(f.time_s).position - f.position).norm(), 0.0, 1e-15);
      EXPECT_NEAR(f.distance_m, (f.position - point).norm(), 1e-18);
    }
    EXPECT_NEAR(newton.distance_m, steffensen.distance_m, 1e-12);
  }
}

}  // namespace
}  // namespace netmc::control
