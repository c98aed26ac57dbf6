#include "control/trajectory/point_ellipse_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace netmc::control {
namespace {

// Root of F(s) = (r0 z0 / (s + r0))^2 + (z1 / (s + 1))^2 - 1 by bisection (monotone in s).
double ellipse_root(double r0, double z0, double z1, double g) {
  const double n0 = r0 * z0;
  double s0 = z1 - 1.0;
  double s1 = g < 0.0 ? 0.0 : std::hypot(n0, z1) - 1.0;
  double s = 0.0;
  for (int i = 0; i < 1100; ++i) {
    s = 0.5 * (s0 + s1);
    if (s == s0 || s == s1) break;
    const double ratio0 = n0 / (s + r0);
    const double ratio1 = z1 / (s + 1.0);
    const double value = ratio0 * ratio0 + ratio1 * ratio1 - 1.0;
    if (value > 0.0) {
      s0 = s;
    } else if (value < 0.0) {
      s1 = s;
    } else {
      break;
    }
  }
  return s;
}

// First quadrant, e0 >= e1 > 0, y0, y1 >= 0. Returns the foot point (x0, x1).
Eigen::Vector2d first_quadrant_foot(double e0, double e1, double y0, double y1) {
  if (y1 > 0.0) {
    if (y0 > 0.0) {
      const double z0 = y0 / e0;
      const double z1 = y1 / e1;
      const double g = z0 * z0 + z1 * z1 - 1.0;
      if (g == 0.0) return {y0, y1};
      const double r0 = (e0 / e1) * (e0 / e1);
      const double s = ellipse_root(r0, z0, z1, g);
      return {r0 * y0 / (s + r0), y1 / (s + 1.0)};
    }
    return {0.0, e1};
  }
  const double numerator = e0 * y0;
  const double denominator = e0 * e0 - e1 * e1;
  if (numerator < denominator) {
    const double ratio = numerator / denominator;
    return {e0 * ratio, e1 * std::sqrt(std::max(0.0, 1.0 - ratio * ratio))};
  }
  return {e0, 0.0};
}

}  // namespace

EllipseFootPoint nearest_point_on_ellipse(double semi_axis_x, double semi_axis_y,
                                          const Eigen::Vector2d& query) {
  // Reduce to the first quadrant with the major axis first, then map the foot point back.
  const bool swap = semi_axis_y > semi_axis_x;
  const double e0 = swap ? semi_axis_y : semi_axis_x;
  const double e1 = swap ? semi_axis_x : semi_axis_y;
  const double q0 = swap ? query.y() : query.x();
  const double q1 = swap ? query.x() : query.y();
  const Eigen::Vector2d foot = first_quadrant_foot(e0, e1, std::abs(q0), std::abs(q1));
  const double f0 = std::copysign(foot.x(), q0);
  const double f1 = std::copysign(foot.y(), q1);
  EllipseFootPoint result;
  result.point = swap ? Eigen::Vector2d(f1, f0) : Eigen::Vector2d(f0, f1);
  const double distance = (query - result.point).norm();
  const double level = (query.x() / semi_axis_x) * (query.x() / semi_axis_x) +
                       (query.y() / semi_axis_y) * (query.y() / semi_axis_y);
  result.signed_distance = level < 1.0 ? -distance : distance;
  return result;
}

}  // namespace netmc::control
