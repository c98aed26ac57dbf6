#include "control/trajectory/spatial_circle.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

SpatialCircle::SpatialCircle(const SpatialCircleParameters& p)
    : center_(p.center),
      radius_(require_positive(p.radius_m, "spatial circle radius")),
      rate_(2.0 * std::numbers::pi / require_positive(p.period_s, "spatial circle period")),
      period_s_(p.period_s) {
  if (!(p.normal.norm() > 0.0)) throw std::invalid_argument("spatial circle normal: expected a non-zero vector");
  normal_ = p.normal.normalized();
  const Eigen::Vector3d in_plane = p.start - p.start.dot(normal_) * normal_;
  if (!(in_plane.norm() > 1e-9 * p.start.norm())) {
    throw std::invalid_argument("spatial circle start: expected a direction not parallel to the normal");
  }
  first_ = in_plane.normalized();
  second_ = normal_.cross(first_);  // counter-clockwise about the normal
}

SpatialReferencePoint SpatialCircle::sample(double time_s) const {
  const double angle = rate_ * time_s;
  const Eigen::Vector3d radial = std::cos(angle) * first_ + std::sin(angle) * second_;
  const Eigen::Vector3d tangent = -std::sin(angle) * first_ + std::cos(angle) * second_;
  SpatialReferencePoint out;
  out.position = center_ + radius_ * radial;
  out.velocity = radius_ * rate_ * tangent;
  out.acceleration = -radius_ * rate_ * rate_ * radial;
  return out;
}

double SpatialCircle::distance(const Eigen::Vector3d& q) const {
  const Eigen::Vector3d d = q - center_;
  const double height = normal_.dot(d);
  const double in_plane = (d - height * normal_).norm();
  return std::hypot(in_plane - radius_, height);
}

SpatialTaskCoordinates SpatialCircle::at(const Eigen::Vector3d& q) const {
  const Eigen::Vector3d d = q - center_;
  const double a = first_.dot(d), b = second_.dot(d);
  const double planar2 = a * a + b * b;
  if (!(planar2 > 0.0)) throw std::invalid_argument("spatial task frame: undefined on the circle's axis");
  const double rho = d.norm();
  SpatialTaskCoordinates out;
  out.r << rho - radius_, normal_.dot(d), radius_ * std::atan2(b, a);
  // Gradients: of |d| (eq. 6-5), of n . d (6-6), of R atan2(b, a) = R (a e2 - b e1) / (a^2 + b^2).
  out.jacobian.row(0) = (d / rho).transpose();
  out.jacobian.row(1) = normal_.transpose();
  out.jacobian.row(2) = (radius_ * (a * second_ - b * first_) / planar2).transpose();
  return out;
}

double SpatialCircle::perimeter_m() const { return 2.0 * std::numbers::pi * radius_; }

std::string SpatialCircle::describe() const {
  std::ostringstream out;
  out << "spatial circle(r=" << radius_ * 1e3 << " mm, centre=(" << center_.transpose() * 1e3
      << ") mm, normal=(" << normal_.transpose() << "), period=" << 2.0 * std::numbers::pi / rate_ << " s)";
  return out.str();
}

}  // namespace netmc::control
