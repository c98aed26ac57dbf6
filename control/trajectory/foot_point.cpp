#include "control/trajectory/foot_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace netmc::control {
namespace {

// The fixed-point map phi of paper 002 (eq. 41) from one evaluation c = C(t). At a cusp (C' = 0)
// it stays put.
double phi(const ReferencePoint& c, const Eigen::Vector2d& point, double t) {
  const double speed2 = c.velocity.squaredNorm();
  if (speed2 < 1e-18) return t;
  return t - (c.position - point).dot(c.velocity) / speed2;
}

double clamp_time(const ReferenceTrajectory& curve, double t) {
  return std::clamp(t, 0.0, curve.duration_s());
}

FootPoint at(const ReferencePoint& c, const Eigen::Vector2d& point, double t, int iterations, int evaluations) {
  return {t, (c.position - point).norm(), iterations, evaluations, c.position, c.velocity};
}

}  // namespace

// One curve evaluation per iteration. On convergence (the step phi(t) - t within tolerance) the
// evaluation at t is the foot point's: the distance is stationary there, so stopping one step
// short changes it by O(|C'|^2 tolerance^2 / distance), below 1e-18 m here.
FootPoint newton_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point,
                            double t0, const FootPointOptions& options) {
  double t = clamp_time(curve, t0);
  ReferencePoint c = curve.sample(t);
  int i = 0, evaluations = 1;
  while (i < options.max_iterations) {
    const double next = clamp_time(curve, phi(c, point, t));
    ++i;
    if (std::abs(next - t) < options.tolerance_s) break;
    t = next;
    c = curve.sample(t);
    ++evaluations;
  }
  return at(c, point, t, i, evaluations);
}

// Two curve evaluations per full iteration (phi(t) and phi(phi(t))), one for the last when phi(t)
// already lands within tolerance: Steffensen is cheaper than Newton only where Newton needs more
// than twice its iterations (docs/reproductions/paper-002.md, "Contour-error estimation cost").
FootPoint steffensen_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point,
                                double t0, const FootPointOptions& options) {
  double t = clamp_time(curve, t0);
  ReferencePoint c = curve.sample(t);
  int i = 0, evaluations = 1;
  while (i < options.max_iterations) {
    const double p1 = clamp_time(curve, phi(c, point, t));
    ++i;
    if (std::abs(p1 - t) < options.tolerance_s) break;
    const ReferencePoint c1 = curve.sample(p1);
    ++evaluations;
    const double p2 = clamp_time(curve, phi(c1, point, p1));
    if (std::abs(p2 - p1) < options.tolerance_s) {  // converged at p1: no extrapolation needed
      t = p1;
      c = c1;
      break;
    }
    const double denominator = p2 - 2.0 * p1 + t;
    // eq. 46; with a vanishing denominator the plain fixed-point step is taken (netmc's choice [A]).
    t = clamp_time(curve, std::abs(denominator) < 1e-15 ? p2 : t - (p1 - t) * (p1 - t) / denominator);
    c = curve.sample(t);
    ++evaluations;
  }
  return at(c, point, t, i, evaluations);
}

SampledContour sample_contour(const CurvePosition& position, double span, int samples) {
  SampledContour grid;
  grid.span = span;
  grid.positions.reserve(static_cast<std::size_t>(samples) + 1);
  for (int i = 0; i <= samples; ++i) grid.positions.push_back(position(span * i / samples));
  constexpr std::size_t kRun = 64;
  for (std::size_t first = 0; first < grid.positions.size(); first += kRun) {
    SampledContour::Run run;
    run.first = first;
    run.count = std::min(kRun, grid.positions.size() - first);
    Eigen::Vector2d low = grid.positions[first], high = low;
    for (std::size_t i = first; i < first + run.count; ++i) {
      low = low.cwiseMin(grid.positions[i]);
      high = high.cwiseMax(grid.positions[i]);
    }
    run.center = 0.5 * (low + high);
    for (std::size_t i = first; i < first + run.count; ++i) {
      run.radius = std::max(run.radius, (grid.positions[i] - run.center).norm());
    }
    grid.runs.push_back(run);
  }
  return grid;
}

SampledContour sample_contour(const ReferenceTrajectory& curve) {
  return sample_contour([&](double t) { return curve.sample(t).position; }, curve.duration_s());
}

CurveEvaluation curve_of(const ReferenceTrajectory& trajectory) {
  return [&trajectory](double t) {
    const ReferencePoint r = trajectory.sample(t);
    return CurvePoint{r.position, r.velocity, r.acceleration};
  };
}

namespace {

// Newton on g(u) = (C - P) . C' = 0 from the nearest sample, safeguarded by bisection within the
// sample intervals on either side; the sample itself when it is nearer (a corner, a clamped end).
FootPoint refine(const SampledContour& grid, const CurveEvaluation& curve, const Eigen::Vector2d& point,
                 std::size_t best_i, double best2) {
  const double span = grid.span;
  const auto samples = static_cast<double>(grid.positions.size() - 1);
  const double best_t = span * static_cast<double>(best_i) / samples;
  // g(u) = (C - P) . C' is negative before the foot point and positive after it; its derivative
  // is |C'|^2 + (C - P) . C''. Newton steps that leave the bracket are replaced by bisection.
  double lo = std::max(0.0, best_t - span / samples);
  double hi = std::min(span, best_t + span / samples);
  double t = best_t;
  for (int i = 0; i < 60; ++i) {
    const CurvePoint c = curve(t);
    const Eigen::Vector2d offset = c.position - point;
    const double g = offset.dot(c.first);
    const double slope = c.first.squaredNorm() + offset.dot(c.second);
    if (g < 0.0) {
      lo = t;
    } else {
      hi = t;
    }
    double next = slope > 0.0 ? t - g / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool converged = std::abs(next - t) < 1e-13 * span || hi - lo < 1e-13 * span;
    t = next;
    if (converged) break;
  }
  const double d = (curve(t).position - point).norm();
  const double best = std::sqrt(best2);
  // The grid point itself can be nearer than the refined one (a corner, a clamped end).
  if (best < d) return {best_t, best, 0};
  return {t, d, 0};
}

}  // namespace

FootPoint nearest_on_contour(const SampledContour& grid, const CurveEvaluation& curve,
                             const Eigen::Vector2d& point) {
  std::size_t best_i = 0;
  double best2 = std::numeric_limits<double>::infinity();
  const auto scan = [&](const SampledContour::Run& run) {
    for (std::size_t i = run.first; i < run.first + run.count; ++i) {
      const double d2 = (grid.positions[i] - point).squaredNorm();
      if (d2 < best2) {
        best2 = d2;
        best_i = i;
      }
    }
  };
  const auto lower_bound = [&](const SampledContour::Run& run) {
    return std::max(0.0, (point - run.center).norm() - run.radius);
  };
  // The most promising run first, then only the runs that could hold a nearer sample.
  std::size_t first_run = 0;
  double nearest_bound = std::numeric_limits<double>::infinity();
  for (std::size_t r = 0; r < grid.runs.size(); ++r) {
    const double bound = lower_bound(grid.runs[r]);
    if (bound < nearest_bound) {
      nearest_bound = bound;
      first_run = r;
    }
  }
  scan(grid.runs[first_run]);
  for (std::size_t r = 0; r < grid.runs.size(); ++r) {
    const double bound = lower_bound(grid.runs[r]);
    if (r != first_run && bound * bound <= best2) scan(grid.runs[r]);
  }
  return refine(grid, curve, point, best_i, best2);
}

FootPoint nearest_on_contour(const SampledContour& grid, const CurveEvaluation& curve,
                             const Eigen::Vector2d& point, std::size_t first, std::size_t last) {
  const std::size_t size = grid.positions.size();
  first = std::min(first, size - 1);
  last = std::min(last, size - 1);
  std::size_t best_i = first;
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = first;; i = (i + 1) % size) {
    const double d2 = (grid.positions[i] - point).squaredNorm();
    if (d2 < best2) {
      best2 = d2;
      best_i = i;
    }
    if (i == last) break;
  }
  return refine(grid, curve, point, best_i, best2);
}

FootPoint exact_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point) {
  return nearest_on_contour(sample_contour(curve), curve_of(curve), point);
}

}  // namespace netmc::control
