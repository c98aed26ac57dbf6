#include "control/contour_error/corner_foot_point.hpp"

#include <cmath>

namespace netmc::control {

FootPoint corner_checked_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point,
                                    double t0, LocalFootPointMethod method,
                                    const CornerCheckOptions& options) {
  FootPoint best = method(curve, point, t0, options.local);
  const std::vector<double> corners = curve.corner_times_s();
  if (corners.empty()) return best;
  const double duration = curve.duration_s();
  const double window = options.window_s > 0.0 ? options.window_s : 0.05 * duration;
  const bool closed = (curve.sample(duration).position - curve.sample(0.0).position).norm() < 1e-9;
  const double local_time = best.time_s;
  int iterations = best.iterations;
  int evaluations = best.evaluations + 2;  // the closed-curve check above
  for (const double corner : corners) {
    double offset = local_time - corner;
    if (closed) offset = std::remainder(offset, duration);  // a corner at 0 is also one at the end
    if (std::abs(offset) > window) continue;
    double mirror = corner - offset;
    if (closed) mirror -= duration * std::floor(mirror / duration);
    const FootPoint other = method(curve, point, mirror, options.local);
    iterations += other.iterations;
    evaluations += other.evaluations;
    if (other.distance_m < best.distance_m) best = other;
  }
  best.iterations = iterations;
  best.evaluations = evaluations;
  return best;
}

}  // namespace netmc::control
