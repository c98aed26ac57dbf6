#include "control/trajectory/circle_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

CircleTrajectory::CircleTrajectory(const CircleParameters& parameters) : p_(parameters) {
  require_finite(p_.center.x(), "circle cx");
  require_finite(p_.center.y(), "circle cy");
  require_positive(p_.radius_m, "circle r");
  require_positive(p_.period_s, "circle period");
  require_finite(p_.start_angle_rad, "circle start angle");
  require_positive(p_.revolutions, "circle revolutions");
  require_non_negative(p_.ramp_s, "circle ramp");
  if (p_.ramp_s > 0.5 * duration_s()) {
    throw std::invalid_argument("circle ramp: expected at most half the duration (" + std::to_string(0.5 * duration_s()) +
                                " s), got " + std::to_string(p_.ramp_s));
  }
  angular_rate_ = (p_.clockwise ? -2.0 : 2.0) * std::numbers::pi / p_.period_s;
  // Each ramp covers half the angle the cruise rate would in the same time.
  if (p_.ramp_s > 0.0) angular_rate_ *= duration_s() / (duration_s() - p_.ramp_s);
}

CircleTrajectory::AngleState CircleTrajectory::ramp_in(double t) const {
  // The quintic in t through angle, rate and angular acceleration at both ends (0, 0, 0 at rest;
  // w T/2, w, 0 at the ramp's end); with the end angle w T/2 its t^5 coefficient is zero:
  // angle = w T (s^3 - s^4/2), s = t/T.
  const double w = angular_rate_, ramp = p_.ramp_s, s = t / ramp;
  return {w * ramp * s * s * s * (1.0 - 0.5 * s), w * s * s * (3.0 - 2.0 * s), w / ramp * 6.0 * s * (1.0 - s)};
}

CircleTrajectory::AngleState CircleTrajectory::angle_at(double time_s) const {
  const double w = angular_rate_;
  if (p_.ramp_s <= 0.0) return {w * time_s, w, 0.0};
  const double duration = duration_s(), ramp = p_.ramp_s;
  const double t = std::clamp(time_s, 0.0, duration);
  if (t <= ramp) return ramp_in(t);
  if (t < duration - ramp) return {w * (t - 0.5 * ramp), w, 0.0};
  // The ramp-out mirrors the ramp-in, measured back from the end angle.
  const double total = w * (duration - ramp);
  const AngleState mirrored = ramp_in(duration - t);
  return {total - mirrored.angle, mirrored.rate, -mirrored.acceleration};
}

ReferencePoint CircleTrajectory::sample(double time_s) const {
  const AngleState a = angle_at(time_s);
  const double angle = p_.start_angle_rad + a.angle;
  const Eigen::Vector2d radial(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d tangent(-radial.y(), radial.x());
  ReferencePoint point;
  point.position = p_.center + p_.radius_m * radial;
  point.velocity = p_.radius_m * a.rate * tangent;
  point.acceleration = p_.radius_m * a.acceleration * tangent - p_.radius_m * a.rate * a.rate * radial;
  return point;
}

double CircleTrajectory::duration_s() const { return p_.revolutions * p_.period_s; }

double CircleTrajectory::contour_error(const Eigen::Vector2d& point) const {
  return (point - p_.center).norm() - p_.radius_m;
}

std::unique_ptr<ReferenceTrajectory> CircleTrajectory::clone() const {
  return std::make_unique<CircleTrajectory>(*this);
}

std::string CircleTrajectory::describe() const {
  std::ostringstream text;
  text << "circle(r=" << p_.radius_m * 1e3 << " mm, centre=(" << p_.center.x() * 1e3 << ", "
       << p_.center.y() * 1e3 << ") mm, period=" << p_.period_s << " s"
       << (p_.clockwise ? ", clockwise" : "");
  if (p_.ramp_s > 0.0) text << ", ramp=" << p_.ramp_s << " s, at rest after " << duration_s() << " s";
  text << ")";
  return text.str();
}

}  // namespace netmc::control
