#pragma once
// Foot point of a point P on a desired motion C(t): the time t* whose position is nearest to P,
// solving (C(t) - P) . C'(t) = 0. The contour error is |P - C(t*)|. Three ways (paper 002, sec. 4):
//   Newton:     t+ = phi(t) = t - (C(t) - P) . C'(t) / |C'(t)|^2   (paper 002, eq. 41, linear convergence)
//   Steffensen: t+ = t - (phi(t) - t)^2 / (phi(phi(t)) - 2 phi(t) + t)   (paper 002, eq. 46)
//   exact:      global search over the whole curve, then refinement (ground truth).

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "control/trajectory/planar_curve.hpp"
#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct FootPoint {
  double time_s = 0.0;       // t*
  double distance_m = 0.0;   // |P - C(t*)|
  int iterations = 0;        // updates of t (the exact search reports 0)
  int evaluations = 0;       // evaluations of the curve C(t), C'(t): what the time goes into
  // C(t*) and C'(t*) where the local iterations evaluated them (zero from the exact search).
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
};

struct FootPointOptions {
  double tolerance_s = 1e-9;  // stop when |t+ - t| < tolerance (paper 002 gives none: netmc's choice [A])
  int max_iterations = 20;
};

// Local iterations from the warm start `t0` (e.g. the desired time, or the previous estimate).
FootPoint newton_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point,
                            double t0, const FootPointOptions& options = {});
FootPoint steffensen_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point,
                                double t0, const FootPointOptions& options = {});
// Global: dense sampling of [0, duration], then golden-section refinement around the best.
FootPoint exact_foot_point(const ReferenceTrajectory& curve, const Eigen::Vector2d& point);

// The dense grid of the global search, sampled once for repeated queries on one curve C(u),
// u in [0, span] (the search then costs one curve evaluation per refinement step, not per sample).
struct SampledContour {
  double span = 0.0;
  std::vector<Eigen::Vector2d> positions;  // C(span i / (size - 1))
  // Runs of consecutive samples in a bounding circle, so that the search skips the runs that
  // cannot hold a nearer sample than the best so far (same result as scanning every sample).
  struct Run {
    std::size_t first = 0, count = 0;
    Eigen::Vector2d center = Eigen::Vector2d::Zero();
    double radius = 0.0;
  };
  std::vector<Run> runs;
};
using CurvePosition = std::function<Eigen::Vector2d(double)>;
using CurveEvaluation = std::function<CurvePoint(double)>;  // C, C', C'' at u
SampledContour sample_contour(const CurvePosition& position, double span, int samples = 4000);
SampledContour sample_contour(const ReferenceTrajectory& curve);
// The global search of exact_foot_point on a pre-sampled curve (time_s is the parameter u): the
// nearest grid point, then Newton on (C(u) - P) . C'(u) = 0 safeguarded by bisection inside the
// grid interval on either side (a handful of curve evaluations instead of a golden-section search).
FootPoint nearest_on_contour(const SampledContour& grid, const CurveEvaluation& curve,
                             const Eigen::Vector2d& point);
// The same, with the samples restricted to indices first..last (wrapping past the end when
// first > last): a local search along the contour, where the global one would jump between
// branches of a contour that comes back near itself (the crossings of a Lissajous figure).
FootPoint nearest_on_contour(const SampledContour& grid, const CurveEvaluation& curve,
                             const Eigen::Vector2d& point, std::size_t first, std::size_t last);
CurveEvaluation curve_of(const ReferenceTrajectory& trajectory);  // u = t

}  // namespace netmc::control
