#pragma once
// Interpolating cubic spline through given points, twice continuously differentiable (so the
// reference acceleration is continuous), parameterised by chord length: natural end conditions
// when open, periodic when the last point equals the first.

#include <vector>

#include "control/trajectory/planar_curve.hpp"

namespace netmc::control {

class CubicSplineCurve final : public PlanarCurve {
 public:
  explicit CubicSplineCurve(std::vector<Eigen::Vector2d> points);

  CurvePoint evaluate(double u) const override;
  double span() const override { return knots_.back(); }
  bool closed() const override { return closed_; }
  int pieces() const override { return static_cast<int>(points_.size()) - 1; }
  std::string describe() const override;

 private:
  std::vector<Eigen::Vector2d> points_;
  std::vector<double> knots_;                 // cumulative chord length
  std::vector<Eigen::Vector2d> curvatures_;   // second derivatives at the knots
  bool closed_ = false;
};

}  // namespace netmc::control
