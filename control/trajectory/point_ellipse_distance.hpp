#pragma once
// Exact distance from a point to an axis-aligned ellipse: the robust bisection of Eberly,
// "Distance from a Point to an Ellipse, an Ellipsoid, or a Hyperellipsoid" (2013), accurate to
// machine precision for any point, including near the centre and the high-curvature vertices.

#include <Eigen/Dense>

namespace netmc::control {

struct EllipseFootPoint {
  Eigen::Vector2d point;   // nearest point on the ellipse, ellipse-centred coordinates
  double signed_distance;  // positive outside
};

// Ellipse x^2/a^2 + y^2/b^2 = 1 centred at the origin; `query` in the same coordinates.
EllipseFootPoint nearest_point_on_ellipse(double semi_axis_x, double semi_axis_y,
                                          const Eigen::Vector2d& query);

}  // namespace netmc::control
