#pragma once
// Motion along a geometric curve at a commanded feed (speed along the arc length), slowing where
// the curve bends so that the normal acceleration v^2 kappa stays within a limit, and changing
// speed with a limited tangential acceleration; from rest to rest. The speed is planned on a
// table of arc length (the usual forward-backward pass): each table interval has a constant
// tangential acceleration, so s(t) is a piecewise quadratic, and the position C(u(s(t))) uses
// the exact inverse of the arc length, so velocity and acceleration are the analytic chain rule.

#include <memory>
#include <vector>

#include "control/trajectory/foot_point.hpp"
#include "control/trajectory/planar_curve.hpp"
#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct FeedRateLimits {
  double feed_m_s = 0.01;                      // commanded speed
  double normal_acceleration_m_s2 = 0.1;       // v^2 kappa <= this
  double tangential_acceleration_m_s2 = 0.1;   // |dv/dt| <= this
};

class FeedRateTrajectory final : public ReferenceTrajectory {
 public:
  // `intervals`: arc-length table size; 0 picks max(4096, 64 per curve piece).
  FeedRateTrajectory(std::shared_ptr<const PlanarCurve> curve, const FeedRateLimits& limits,
                     int intervals = 0);

  ReferencePoint sample(double time_s) const override;
  double duration_s() const override { return times_.back(); }
  // Distance to the exact foot point on the curve (global search). Closed curves: positive
  // outside (on the right of travel when it runs counter-clockwise); open or self-intersecting:
  // positive on the right of travel.
  double contour_error(const Eigen::Vector2d& point) const override;
  std::unique_ptr<ReferenceTrajectory> clone() const override;
  std::string describe() const override;

  double length_m() const { return arcs_.back(); }
  double arc_length(double u) const;  // from u = 0, by Gauss quadrature on the table interval
  const PlanarCurve& curve() const { return *curve_; }

 private:
  std::size_t interval_of_parameter(double u) const;
  double parameter_at(double s, std::size_t interval) const;  // exact inverse of arc_length

  std::shared_ptr<const PlanarCurve> curve_;
  FeedRateLimits limits_;
  double step_u_ = 0.0;                 // table spacing in u
  std::vector<double> arcs_;            // s at u = step_u i
  std::vector<double> speeds_;          // planned speed at the table points
  std::vector<double> times_;           // time of reaching each table point
  double orientation_ = 1.0;            // -1 for a clockwise closed curve
  SampledContour grid_;
};

}  // namespace netmc::control
