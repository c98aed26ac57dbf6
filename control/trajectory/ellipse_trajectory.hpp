#pragma once
// Motion around an axis-aligned ellipse at uniform parameter rate: x = cx + a cos(phi),
// y = cy + b sin(phi), phi = phi0 +/- 2 pi t / period. Curvature varies along the contour, which
// is what makes it a harder test than the circle.

#include "control/trajectory/planar_curve.hpp"
#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct EllipseParameters {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double semi_axis_x_m = 0.02;   // a
  double semi_axis_y_m = 0.01;   // b
  double period_s = 8.0;
  double start_angle_rad = 0.0;
  bool clockwise = false;
  double revolutions = 1.0;
};

// One revolution of the same ellipse as a geometric curve, u in [0, 2 pi] from the start angle
// in the direction of travel (the period and revolutions are ignored), for a feed-rate profile
// (FeedRateTrajectory) instead of the uniform parameter rate.
class EllipseCurve final : public PlanarCurve {
 public:
  explicit EllipseCurve(const EllipseParameters& parameters);
  CurvePoint evaluate(double u) const override;
  double span() const override;
  bool closed() const override { return true; }
  std::string describe() const override;

 private:
  EllipseParameters p_;
};

class EllipseTrajectory final : public ReferenceTrajectory {
 public:
  explicit EllipseTrajectory(const EllipseParameters& parameters);

  ReferencePoint sample(double time_s) const override;
  double duration_s() const override;
  double period_s() const override { return p_.period_s; }
  double contour_error(const Eigen::Vector2d& point) const override;
  std::unique_ptr<ReferenceTrajectory> clone() const override;
  std::string describe() const override;
  const EllipseParameters& parameters() const { return p_; }

 private:
  EllipseParameters p_;
  double angular_rate_;
};

}  // namespace netmc::control
