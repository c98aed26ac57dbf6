#include "control/trajectory/ellipse_trajectory.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "control/parameter_check.hpp"
#include "control/trajectory/point_ellipse_distance.hpp"

namespace netmc::control {

EllipseTrajectory::EllipseTrajectory(const EllipseParameters& parameters) : p_(parameters) {
  require_finite(p_.center.x(), "ellipse cx");
  require_finite(p_.center.y(), "ellipse cy");
  require_positive(p_.semi_axis_x_m, "ellipse a");
  require_positive(p_.semi_axis_y_m, "ellipse b");
  require_positive(p_.period_s, "ellipse period");
  require_finite(p_.start_angle_rad, "ellipse start angle");
  require_positive(p_.revolutions, "ellipse revolutions");
  angular_rate_ = (p_.clockwise ? -2.0 : 2.0) * std::numbers::pi / p_.period_s;
}

ReferencePoint EllipseTrajectory::sample(double time_s) const {
  const double angle = p_.start_angle_rad + angular_rate_ * time_s;
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double a = p_.semi_axis_x_m;
  const double b = p_.semi_axis_y_m;
  const double w = angular_rate_;
  ReferencePoint point;
  point.position = p_.center + Eigen::Vector2d(a * c, b * s);
  point.velocity = Eigen::Vector2d(-a * w * s, b * w * c);
  point.acceleration = Eigen::Vector2d(-a * w * w * c, -b * w * w * s);
  return point;
}

double EllipseTrajectory::duration_s() const { return p_.revolutions * p_.period_s; }

double EllipseTrajectory::contour_error(const Eigen::Vector2d& point) const {
  return nearest_point_on_ellipse(p_.semi_axis_x_m, p_.semi_axis_y_m, point - p_.center)
      .signed_distance;
}

std::unique_ptr<ReferenceTrajectory> EllipseTrajectory::clone() const {
  return std::make_unique<EllipseTrajectory>(*this);
}

std::string EllipseTrajectory::describe() const {
  std::ostringstream text;
  text << "ellipse(a=" << p_.semi_axis_x_m * 1e3 << " mm, b=" << p_.semi_axis_y_m * 1e3
       << " mm, centre=(" << p_.center.x() * 1e3 << ", " << p_.center.y() * 1e3
       << ") mm, period=" << p_.period_s << " s" << (p_.clockwise ? ", clockwise" : "") << ")";
  return text.str();
}

EllipseCurve::EllipseCurve(const EllipseParameters& parameters) : p_(EllipseTrajectory(parameters).parameters()) {}

double EllipseCurve::span() const { return 2.0 * std::numbers::pi; }

CurvePoint EllipseCurve::evaluate(double u) const {
  const double direction = p_.clockwise ? -1.0 : 1.0;
  const double angle = p_.start_angle_rad + direction * u;
  const double a = p_.semi_axis_x_m, b = p_.semi_axis_y_m;
  const double c = std::cos(angle), s = std::sin(angle);
  CurvePoint point;
  point.position = p_.center + Eigen::Vector2d(a * c, b * s);
  point.first = direction * Eigen::Vector2d(-a * s, b * c);
  point.second = Eigen::Vector2d(-a * c, -b * s);
  return point;
}

std::string EllipseCurve::describe() const {
  std::ostringstream text;
  text << "ellipse(a=" << p_.semi_axis_x_m * 1e3 << " mm, b=" << p_.semi_axis_y_m * 1e3
       << " mm, centre=(" << p_.center.x() * 1e3 << ", " << p_.center.y() * 1e3 << ") mm"
       << (p_.clockwise ? ", clockwise" : "") << ")";
  return text.str();
}

}  // namespace netmc::control
