#pragma once
// Straight segments through given points with sharp corners: the motion decelerates to the
// corner speed (0: a full stop) at every corner, accelerating at most `max_acceleration` and
// moving at most `max_speed` (a trapezoidal speed profile per segment, a triangle when the
// segment is too short to reach the top speed). Closed when the last point equals the first;
// the motion starts and ends at rest either way. With a jerk limit each segment is instead a
// rest-to-rest S-curve (JerkLimitedMove): acceleration continuous, a full stop at every corner.

#include <vector>

#include "control/trajectory/jerk_limited_move.hpp"
#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct PolylineParameters {
  std::vector<Eigen::Vector2d> points;
  double max_speed_m_s = 0.01;
  double max_acceleration_m_s2 = 0.1;
  double corner_speed_m_s = 0.0;  // at the inner corners; the velocity turns there abruptly
  double max_jerk_m_s3 = 0.0;     // > 0: jerk-limited, stopping at every corner; 0: trapezoidal
};

class PolylineTrajectory final : public ReferenceTrajectory {
 public:
  explicit PolylineTrajectory(const PolylineParameters& parameters);

  ReferencePoint sample(double time_s) const override;
  double duration_s() const override { return start_time_.back(); }
  // Closed form: distance to the nearest segment. Closed polylines: positive outside; open ones:
  // positive on the right of travel (at a corner, the side of the bisector of the two normals).
  double contour_error(const Eigen::Vector2d& point) const override;
  // The inner vertices (and the start of a closed polyline, where it ends too).
  std::vector<double> corner_times_s() const override;
  std::unique_ptr<ReferenceTrajectory> clone() const override;
  std::string describe() const override;

  bool closed() const { return closed_; }
  double length_m() const { return start_arc_.back(); }

 private:
  struct Segment {
    Eigen::Vector2d start, end, direction;
    double length = 0.0;
    double entry_speed = 0.0, peak_speed = 0.0, exit_speed = 0.0;
    double accelerate_s = 0.0, cruise_s = 0.0, decelerate_s = 0.0;
  };
  Eigen::Vector2d right_normal(std::size_t segment) const;

  PolylineParameters p_;
  bool closed_ = false;
  double orientation_ = 1.0;  // -1 for a clockwise closed polyline (outside is on the left)
  std::vector<Segment> segments_;
  std::vector<JerkLimitedMove> moves_;  // one per segment when jerk-limited, else empty
  std::vector<double> start_time_;  // of each segment, then the end
  std::vector<double> start_arc_;   // arc length at each segment's start, then the total
};

}  // namespace netmc::control
