#pragma once
// A geometric planar curve C(u), u in [0, span], with its first two derivatives in u: the shape
// alone, before a speed profile (FeedRateTrajectory) turns it into a motion.

#include <Eigen/Dense>
#include <memory>
#include <string>

namespace netmc::control {

struct CurvePoint {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d first = Eigen::Vector2d::Zero();   // dC/du
  Eigen::Vector2d second = Eigen::Vector2d::Zero();  // d2C/du2
};

class PlanarCurve {
 public:
  virtual ~PlanarCurve() = default;
  virtual CurvePoint evaluate(double u) const = 0;
  virtual double span() const = 0;
  // Ends where it starts (with a continuous tangent).
  virtual bool closed() const = 0;
  // Crosses itself, so has no single inside (its contour error is signed by the side of travel).
  virtual bool self_intersecting() const { return false; }
  // Parameters where the curve's derivatives may jump (spline knots); the feed profile's grid
  // is refined to honour them.
  virtual int pieces() const { return 1; }
  virtual std::string describe() const = 0;
};

// Signed curvature (x' y'' - y' x'') / |C'|^3, positive when turning left.
inline double signed_curvature(const CurvePoint& c) {
  const double speed = c.first.norm();
  return (c.first.x() * c.second.y() - c.first.y() * c.second.x()) / (speed * speed * speed);
}

}  // namespace netmc::control
