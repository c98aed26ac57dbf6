#include "control/trajectory/polyline_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

PolylineTrajectory::PolylineTrajectory(const PolylineParameters& parameters) : p_(parameters) {
  require_positive(p_.max_speed_m_s, "polyline vmax");
  require_positive(p_.max_acceleration_m_s2, "polyline amax");
  require_non_negative(p_.corner_speed_m_s, "polyline corner speed");
  require_non_negative(p_.max_jerk_m_s3, "polyline max jerk");
  if (p_.max_jerk_m_s3 > 0.0 && p_.corner_speed_m_s > 0.0) {
    throw std::invalid_argument("polyline corner speed: a jerk-limited polyline stops at every corner; expected 0, got " +
                                std::to_string(p_.corner_speed_m_s));
  }
  const auto& points = p_.points;
  if (points.size() < 2) {
    throw std::invalid_argument("polyline points: expected at least two points, got " +
                                std::to_string(points.size()));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    require_finite(points[i].x(), "polyline point x");
    require_finite(points[i].y(), "polyline point y");
    if (i > 0 && (points[i] - points[i - 1]).norm() <= 0.0) {
      throw std::invalid_argument("polyline points: point " + std::to_string(i + 1) +
                                  " repeats point " + std::to_string(i) + " (segments need a length)");
    }
  }
  closed_ = points.size() > 2 && points.back() == points.front();
  if (closed_ && points.size() < 4) {
    throw std::invalid_argument("polyline points: a closed polyline needs at least three distinct points");
  }
  const std::size_t n = points.size() - 1;
  const double a = p_.max_acceleration_m_s2;
  // Speeds at the vertices: rest at both ends, the corner speed between, then limited so that
  // each segment can change speed within its length (forward, then backward pass).
  std::vector<double> vertex_speed(n + 1, std::min(p_.corner_speed_m_s, p_.max_speed_m_s));
  vertex_speed.front() = vertex_speed.back() = 0.0;
  std::vector<double> lengths(n);
  for (std::size_t k = 0; k < n; ++k) lengths[k] = (points[k + 1] - points[k]).norm();
  for (std::size_t k = 0; k < n; ++k) {
    vertex_speed[k + 1] = std::min(vertex_speed[k + 1], std::sqrt(vertex_speed[k] * vertex_speed[k] + 2 * a * lengths[k]));
  }
  for (std::size_t k = n; k-- > 0;) {
    vertex_speed[k] = std::min(vertex_speed[k], std::sqrt(vertex_speed[k + 1] * vertex_speed[k + 1] + 2 * a * lengths[k]));
  }
  start_time_.assign(1, 0.0);
  start_arc_.assign(1, 0.0);
  double area2 = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    Segment s;
    s.start = points[k];
    s.end = points[k + 1];
    s.length = lengths[k];
    s.direction = (points[k + 1] - points[k]) / s.length;
    s.entry_speed = vertex_speed[k];
    s.exit_speed = vertex_speed[k + 1];
    const double v0 = s.entry_speed, v1 = s.exit_speed;
    s.peak_speed = std::min(p_.max_speed_m_s, std::sqrt(a * s.length + 0.5 * (v0 * v0 + v1 * v1)));
    s.peak_speed = std::max({s.peak_speed, v0, v1});
    const double vp = s.peak_speed;
    const double accelerate_m = (vp * vp - v0 * v0) / (2 * a);
    const double decelerate_m = (vp * vp - v1 * v1) / (2 * a);
    s.accelerate_s = (vp - v0) / a;
    s.decelerate_s = (vp - v1) / a;
    s.cruise_s = std::max(0.0, s.length - accelerate_m - decelerate_m) / vp;
    segments_.push_back(s);
    if (p_.max_jerk_m_s3 > 0.0) {
      moves_.emplace_back(s.length, p_.max_speed_m_s, a, p_.max_jerk_m_s3);
      start_time_.push_back(start_time_.back() + moves_.back().duration_s());
    } else {
      start_time_.push_back(start_time_.back() + s.accelerate_s + s.cruise_s + s.decelerate_s);
    }
    start_arc_.push_back(start_arc_.back() + s.length);
    area2 += points[k].x() * points[k + 1].y() - points[k + 1].x() * points[k].y();
  }
  orientation_ = closed_ && area2 < 0.0 ? -1.0 : 1.0;
}

ReferencePoint PolylineTrajectory::sample(double time_s) const {
  const double t = std::clamp(time_s, 0.0, duration_s());
  const auto after = std::upper_bound(start_time_.begin(), start_time_.end(), t);
  const auto k = std::min(static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - start_time_.begin() - 1, 0)),
                          segments_.size() - 1);
  const Segment& s = segments_[k];
  const double a = p_.max_acceleration_m_s2;
  double tau = t - start_time_[k];
  double along = 0.0, speed = 0.0, acceleration = 0.0;
  if (!moves_.empty()) {
    const MoveState state = moves_[k].at(tau);
    along = state.position;
    speed = state.speed;
    acceleration = state.acceleration;
  } else if (tau < s.accelerate_s) {
    speed = s.entry_speed + a * tau;
    along = s.entry_speed * tau + 0.5 * a * tau * tau;
    acceleration = a;
  } else if (tau < s.accelerate_s + s.cruise_s) {
    along = 0.5 * (s.entry_speed + s.peak_speed) * s.accelerate_s + s.peak_speed * (tau - s.accelerate_s);
    speed = s.peak_speed;
  } else {
    // Decelerating: measured back from the segment's end, which keeps the end point exact.
    const double left = std::max(0.0, s.accelerate_s + s.cruise_s + s.decelerate_s - tau);
    speed = s.exit_speed + a * left;
    along = s.length - (s.exit_speed * left + 0.5 * a * left * left);
    acceleration = left > 0.0 ? -a : 0.0;
  }
  ReferencePoint point;
  point.position = along >= s.length ? s.end : Eigen::Vector2d(s.start + along * s.direction);
  point.velocity = speed * s.direction;
  point.acceleration = acceleration * s.direction;
  return point;
}

Eigen::Vector2d PolylineTrajectory::right_normal(std::size_t segment) const {
  const Eigen::Vector2d& d = segments_[segment].direction;
  return {d.y(), -d.x()};
}

double PolylineTrajectory::contour_error(const Eigen::Vector2d& point) const {
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_k = 0;
  double best_along = 0.0;
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    const Segment& s = segments_[k];
    const double along = std::clamp((point - s.start).dot(s.direction), 0.0, s.length);
    const double distance = (point - s.start - along * s.direction).norm();
    if (distance < best) {
      best = distance;
      best_k = k;
      best_along = along;
    }
  }
  const Eigen::Vector2d offset = point - segments_[best_k].start - best_along * segments_[best_k].direction;
  Eigen::Vector2d normal = right_normal(best_k);
  const std::size_t last = segments_.size() - 1;
  // At a vertex the nearest point is shared by two segments: the bisector of their normals.
  if (best_along <= 0.0 && (best_k > 0 || closed_)) {
    normal += right_normal(best_k > 0 ? best_k - 1 : last);
  } else if (best_along >= segments_[best_k].length && (best_k < last || closed_)) {
    normal += right_normal(best_k < last ? best_k + 1 : 0);
  }
  return orientation_ * (offset.dot(normal) >= 0.0 ? best : -best);
}

std::vector<double> PolylineTrajectory::corner_times_s() const {
  std::vector<double> times;
  if (closed_) times.push_back(0.0);
  times.insert(times.end(), start_time_.begin() + 1, start_time_.end() - 1);
  return times;
}

std::unique_ptr<ReferenceTrajectory> PolylineTrajectory::clone() const {
  return std::make_unique<PolylineTrajectory>(*this);
}

std::string PolylineTrajectory::describe() const {
  std::ostringstream text;
  text << "polyline(" << p_.points.size() << " points" << (closed_ ? ", closed" : "")
       << ", length=" << length_m() * 1e3 << " mm, vmax=" << p_.max_speed_m_s * 1e3
       << " mm/s, amax=" << p_.max_acceleration_m_s2 * 1e3 << " mm/s^2";
  if (p_.corner_speed_m_s > 0.0) text << ", corner=" << p_.corner_speed_m_s * 1e3 << " mm/s";
  if (p_.max_jerk_m_s3 > 0.0) text << ", jmax=" << p_.max_jerk_m_s3 << " m/s^3";
  text << ", " << duration_s() << " s)";
  return text.str();
}

}  // namespace netmc::control
