#include "control/foot_point.hpp"

#include <algorithm>
#include <cmath>

namespace netmc::control {
namespace {

// The fixed-point map phi of paper 002 (eq. 41). At a cusp (C' = 0) it stays put.
double phi(const ReferenceTrajectory& curve, const Eigen::Vector2d& point, double t) {
  const ReferencePoint c = curve.sample(t);
  const double speed2 = c.velocity.squaredNorm();
  if (speed2 < 1e-18) return t;
  return t - (c.position - point).dot(c.velocity) / speed2;
}

double clamp_time(const ReferenceTrajectory& curve, double t) {
  return std::clamp(t, 0.0, curve.duration_s());
}

FootPoint finish(const ReferenceTrajectory& curve, const Eigen::Vector2d& point, double t, int iterations) {
  return {t, (curve.sample(t).position - point).norm(), iterations};
}

}  // namespace

FootPoint newton_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point,
                            double t0, const FootPointOptions& options) {
  double t = clamp_time(curve, t0);
  int i = 0;
  while (i < options.max_iterations) {
    const double next = clamp_time(curve, phi(curve, point, t));
    ++i;
    const bool converged = std::abs(next - t) < options.tolerance_s;
    t = next;
    if (converged) break;
  }
  return finish(curve, point, t, i);
}

FootPoint steffensen_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point,
                                double t0, const FootPointOptions& options) {
  double t = clamp_time(curve, t0);
  int i = 0;
  while (i < options.max_iterations) {
    const double p1 = phi(curve, point, t);
    const double p2 = phi(curve, point, p1);
    const double denominator = p2 - 2.0 * p1 + t;
    ++i;
    // eq. 46; with a vanishing denominator the plain fixed-point step is taken (digest 3.7 [A]).
    const double next = clamp_time(curve, std::abs(denominator) < 1e-15
                                              ? p2
                                              : t - (p1 - t) * (p1 - t) / denominator);
    const bool converged = std::abs(next - t) < options.tolerance_s;
    t = next;
    if (converged) break;
  }
  return finish(curve, point, t, i);
}

FootPoint exact_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point) {
  const double duration = curve.duration_s();
  const int samples = 4000;
  const auto distance = [&](double t) { return (curve.sample(t).position - point).norm(); };
  double best_t = 0.0, best = distance(0.0);
  for (int i = 1; i <= samples; ++i) {
    const double t = duration * i / samples;
    const double d = distance(t);
    if (d < best) {
      best = d;
      best_t = t;
    }
  }
  // Golden-section search on the bracketing interval (the distance is unimodal there).
  double lo = std::max(0.0, best_t - duration / samples);
  double hi = std::min(duration, best_t + duration / samples);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 0; i < 100 && hi - lo > 1e-13 * duration; ++i) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (distance(m1) < distance(m2)) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  const double t = 0.5 * (lo + hi);
  return {t, std::min(distance(t), best), 0};
}

}  // namespace netmc::control
