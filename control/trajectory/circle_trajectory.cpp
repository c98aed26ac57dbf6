#include "control/trajectory/circle_trajectory.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {

CircleTrajectory::CircleTrajectory(const CircleParameters& parameters) : p_(parameters) {
  require_finite(p_.center.x(), "circle cx");
  require_finite(p_.center.y(), "circle cy");
  require_positive(p_.radius_m, "circle r");
  require_positive(p_.period_s, "circle period");
  require_finite(p_.start_angle_rad, "circle start angle");
  require_positive(p_.revolutions, "circle revolutions");
  angular_rate_ = (p_.clockwise ? -2.0 : 2.0) * std::numbers::pi / p_.period_s;
}

ReferencePoint CircleTrajectory::sample(double time_s) const {
  const double angle = p_.start_angle_rad + angular_rate_ * time_s;
  const Eigen::Vector2d radial(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d tangent(-radial.y(), radial.x());
  ReferencePoint point;
  point.position = p_.center + p_.radius_m * radial;
  point.velocity = p_.radius_m * angular_rate_ * tangent;
  point.acceleration = -p_.radius_m * angular_rate_ * angular_rate_ * radial;
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
       << (p_.clockwise ? ", clockwise" : "") << ")";
  return text.str();
}

}  // namespace netmc::control
