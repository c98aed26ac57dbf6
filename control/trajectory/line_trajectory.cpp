#include "control/trajectory/line_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

LineTrajectory::LineTrajectory(const LineParameters& parameters) : p_(parameters) {
  require_finite(p_.start.x(), "line x0");
  require_finite(p_.start.y(), "line y0");
  require_finite(p_.end.x(), "line x1");
  require_finite(p_.end.y(), "line y1");
  require_positive(p_.duration_s, "line duration");
  length_ = (p_.end - p_.start).norm();
  if (!(length_ > 0.0)) {
    throw std::invalid_argument("line: start and end must differ (got a zero-length segment)");
  }
  direction_ = (p_.end - p_.start) / length_;
}

ReferencePoint LineTrajectory::sample(double time_s) const {
  ReferencePoint point;
  point.velocity = (p_.end - p_.start) / p_.duration_s;
  point.position = p_.start + point.velocity * time_s;
  return point;
}

double LineTrajectory::duration_s() const { return p_.duration_s; }

double LineTrajectory::contour_error(const Eigen::Vector2d& point) const {
  const Eigen::Vector2d offset = point - p_.start;
  const double along = std::clamp(offset.dot(direction_), 0.0, length_);
  const double distance = (offset - along * direction_).norm();
  // Cross product sign: negative when the point is to the left of travel.
  const double side = direction_.x() * offset.y() - direction_.y() * offset.x();
  return side > 0.0 ? -distance : distance;
}

std::unique_ptr<ReferenceTrajectory> LineTrajectory::clone() const {
  return std::make_unique<LineTrajectory>(*this);
}

std::string LineTrajectory::describe() const {
  std::ostringstream text;
  text << "line((" << p_.start.x() * 1e3 << ", " << p_.start.y() * 1e3 << ") mm -> ("
       << p_.end.x() * 1e3 << ", " << p_.end.y() * 1e3 << ") mm, " << p_.duration_s << " s)";
  return text.str();
}

}  // namespace netmc::control
