// The single-axis reference of thesis ch. 5 (eq. 5-50): values against the printed formula,
// derivatives against central differences of the position (a second method), the start at rest,
// the 10 s period, and the one-axis group built on it (error x - x_d).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "control/group/single_axis_group.hpp"
#include "control/trajectory/multi_sine_reference.hpp"

namespace netmc::control {
namespace {

TEST(MultiSineReference, IsThesisEquation550) {
  const MultiSineReference reference(thesis_dead_zone_reference(20.0));
  const double pi = std::numbers::pi;
  for (double t : {0.0, 0.37, 1.0, 4.2, 9.99, 13.5}) {
    const double printed = 0.21 + 0.08 * std::sin(pi * t - pi / 2) + 0.07 * std::sin(0.8 * pi * t - pi / 2) +
                           0.06 * std::sin(1.2 * pi * t - pi / 2);
    EXPECT_NEAR(reference.sample(t).position, printed, 1e-15) << t;
  }
  // X(0) = [0, 0] (thesis 5.4): the reference starts where the axis rests.
  EXPECT_NEAR(reference.sample(0.0).position, 0.0, 1e-15);
  EXPECT_NEAR(reference.sample(0.0).velocity, 0.0, 1e-15);
  // Every term repeats within 10 s; none within 5 s.
  EXPECT_NEAR(reference.sample(13.1).position, reference.sample(3.1).position, 1e-14);
  EXPECT_GT(std::abs(reference.sample(8.1).position - reference.sample(3.1).position), 1e-3);
  EXPECT_EQ(reference.period_s(), 10.0);
}

TEST(MultiSineReference, DerivativesMatchCentralDifferences) {
  const MultiSineReference reference(thesis_dead_zone_reference(20.0));
  const double h = 1e-5;
  for (double t : {0.3, 2.9, 7.7}) {
    const auto at = reference.sample(t);
    const double velocity = (reference.sample(t + h).position - reference.sample(t - h).position) / (2 * h);
    const double acceleration = (reference.sample(t + h).velocity - reference.sample(t - h).velocity) / (2 * h);
    EXPECT_NEAR(at.velocity, velocity, 1e-8) << t;
    EXPECT_NEAR(at.acceleration, acceleration, 1e-7) << t;
  }
}

TEST(MultiSineReference, RejectsBadParametersNamingTheField) {
  auto p = thesis_dead_zone_reference(20.0);
  p.terms[1].frequency_hz = 0.0;
  try {
    MultiSineReference bad(p);
    FAIL() << "accepted a zero frequency";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("trajectory.multi_sine.terms.frequency_hz"), std::string::npos);
  }
  p = thesis_dead_zone_reference(20.0);
  p.terms.clear();
  EXPECT_THROW(MultiSineReference{p}, std::invalid_argument);
  p = thesis_dead_zone_reference(std::nan(""));
  EXPECT_THROW(MultiSineReference{p}, std::invalid_argument);
  p = thesis_dead_zone_reference(20.0);
  p.terms.resize(MultiSineReference::kMaxTerms + 1, p.terms[0]);
  EXPECT_THROW(MultiSineReference{p}, std::invalid_argument);
}

TEST(SingleAxisTrack, ItsErrorIsPositionMinusReference) {
  const SingleAxisTrack track(std::make_shared<MultiSineReference>(thesis_dead_zone_reference(20.0)));
  EXPECT_EQ(track.axes(), 1u);
  GroupReference reference;
  track.sample(2.5, reference);
  ASSERT_EQ(reference.position.size(), 1);
  EXPECT_EQ(reference.time_s, 2.5);
  AxisVector point = AxisVector::Constant(1, reference.position[0] + 3e-6);
  EXPECT_NEAR(track.contour_error(point, reference), 3e-6, 1e-15);
  point[0] = reference.position[0] - 1e-3;
  EXPECT_NEAR(track.contour_error(point, reference), -1e-3, 1e-15);
  EXPECT_EQ(track.duration_s(), 20.0);
  EXPECT_EQ(track.period_s(), 10.0);
}

}  // namespace
}  // namespace netmc::control
