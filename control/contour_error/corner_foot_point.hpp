#pragma once
// Foot point near sharp corners. Close to a corner (a cusp of the heart, a polyline vertex) the
// nearest point of the contour can lie on the far side of the corner, where a local iteration
// that follows the tracking record (paper 002's warm-started procedure) never goes: it stays on
// its own branch and reports a contour error up to tens of micrometres too large. A second local
// solve, started at the mirror image of the first solution across the corner, reaches the other
// branch; the nearer of the two foot points is kept. Away from corners nothing changes.

#include <vector>

#include "control/trajectory/foot_point.hpp"

namespace netmc::control {

using LocalFootPointMethod = FootPoint (*)(const ReferenceTrajectory&, const Eigen::Vector2d&,
                                           double, const FootPointOptions&);

struct CornerCheckOptions {
  // Corners within this much of the local solution, in the curve's time, are checked;
  // 0: 5 % of the curve's duration.
  double window_s = 0.0;
  FootPointOptions local;
};

// `method` (newton_foot_point or steffensen_foot_point) from the warm start t0, then from the
// mirror image across each corner of `curve.corner_times_s()` within the window (wrapped on a
// closed curve). The iterations of every solve are added up.
FootPoint corner_checked_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point,
                                    double t0, LocalFootPointMethod method,
                                    const CornerCheckOptions& options = {});

}  // namespace netmc::control
