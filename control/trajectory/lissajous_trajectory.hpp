#pragma once
// A Lissajous figure traced at uniform parameter rate: x = cx + ax sin(p w t + phase),
// y = cy + ay sin(q w t), w = 2 pi / period, p and q positive integers. The curve closes after
// one period and crosses itself, so it has no single inside: its contour error is signed by the
// normal on the right of the direction of travel at the foot point.

#include "control/trajectory/foot_point.hpp"
#include "control/trajectory/planar_curve.hpp"
#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct LissajousParameters {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double amplitude_x_m = 0.02;  // ax
  double amplitude_y_m = 0.02;  // ay
  int frequency_x = 3;          // p
  int frequency_y = 2;          // q
  double phase_rad = 0.0;       // of the x motion
  double period_s = 10.0;
};

// The figure as a geometric curve, u = w t in [0, 2 pi] (the period is ignored): timed at the
// uniform rate by LissajousTrajectory, or by a feed-rate profile (FeedRateTrajectory).
class LissajousCurve final : public PlanarCurve {
 public:
  explicit LissajousCurve(const LissajousParameters& parameters);
  CurvePoint evaluate(double u) const override;
  double span() const override;
  bool closed() const override { return true; }
  bool self_intersecting() const override { return true; }
  std::string describe() const override;

 private:
  LissajousParameters p_;
};

class LissajousTrajectory final : public ReferenceTrajectory {
 public:
  explicit LissajousTrajectory(const LissajousParameters& parameters);

  ReferencePoint sample(double time_s) const override;
  double duration_s() const override { return period_s_; }
  // Distance to the exact foot point (global search), positive on the right of travel.
  double contour_error(const Eigen::Vector2d& point) const override;
  std::unique_ptr<ReferenceTrajectory> clone() const override;
  std::string describe() const override;

 private:
  LissajousCurve curve_;
  double period_s_;
  double rate_;  // w
  SampledContour grid_;  // of the curve, u = w t
};

}  // namespace netmc::control
