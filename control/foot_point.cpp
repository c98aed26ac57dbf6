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

SampledContour sample_contour(const CurvePosition& position, double span, int samples) {
  SampledContour grid;
  grid.span = span;
  grid.positions.reserve(static_cast<std::size_t>(samples) + 1);
  for (int i = 0; i <= samples; ++i) grid.positions.push_back(position(span * i / samples));
  return grid;
}

SampledContour sample_contour(const ReferenceTrajectory& curve) {
  return sample_contour([&](double t) { return curve.sample(t).position; }, curve.duration_s());
}

FootPoint nearest_on_contour(const SampledContour& grid, const CurvePosition& position,
                             const Eigen::Vector2d& point) {
  const double span = grid.span;
  const auto samples = static_cast<double>(grid.positions.size() - 1);
  std::size_t best_i = 0;
  double best2 = (grid.positions[0] - point).squaredNorm();
  for (std::size_t i = 1; i < grid.positions.size(); ++i) {
    const double d2 = (grid.positions[i] - point).squaredNorm();
    if (d2 < best2) {
      best2 = d2;
      best_i = i;
    }
  }
  const double best_t = span * static_cast<double>(best_i) / samples;
  const auto distance = [&](double t) { return (position(t) - point).norm(); };
  // Golden-section search on the bracketing interval (the distance is unimodal there).
  double lo = std::max(0.0, best_t - span / samples);
  double hi = std::min(span, best_t + span / samples);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
  double d1 = distance(m1), d2 = distance(m2);
  for (int i = 0; i < 100 && hi - lo > 1e-13 * span; ++i) {
    if (d1 < d2) {
      hi = m2;
      m2 = m1;
      d2 = d1;
      m1 = hi - g * (hi - lo);
      d1 = distance(m1);
    } else {
      lo = m1;
      m1 = m2;
      d1 = d2;
      m2 = lo + g * (hi - lo);
      d2 = distance(m2);
    }
  }
  const double t = 0.5 * (lo + hi);
  const double d = distance(t);
  const double best = std::sqrt(best2);
  // The grid point itself can be nearer than the refined one (a corner, a clamped end).
  if (best < d) return {best_t, best, 0};
  return {t, d, 0};
}

FootPoint exact_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point) {
  const CurvePosition position = [&](double t) { return curve.sample(t).position; };
  return nearest_on_contour(sample_contour(position, curve.duration_s()), position, point);
}

}  // namespace netmc::control
