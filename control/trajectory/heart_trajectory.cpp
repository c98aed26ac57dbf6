#include "control/trajectory/heart_trajectory.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "control/trajectory/foot_point.hpp"
#include "control/parameter_check.hpp"

namespace netmc::control {

HeartTrajectory::HeartTrajectory(const HeartParameters& parameters) : p_(parameters) {
  require_finite(p_.center.x(), "heart cx");
  require_finite(p_.center.y(), "heart cy");
  require_positive(p_.scale_m, "heart scale");
  require_positive(p_.period_s, "heart period");
  rate_ = 2.0 * std::numbers::pi / p_.period_s;
}

ReferencePoint HeartTrajectory::sample(double time_s) const {
  const double f = rate_ * time_s;
  const double s = std::sin(f), c = std::cos(f);
  // The multiple angles from sin f and cos f alone (one sin/cos pair per sample instead of
  // eight: the foot-point estimators evaluate the heart several times a cycle).
  const double c2 = 2.0 * c * c - 1.0, s2 = 2.0 * s * c;
  const double c3 = c * (2.0 * c2 - 1.0), s3 = s * (2.0 * c2 + 1.0);
  const double c4 = 2.0 * c2 * c2 - 1.0, s4 = 2.0 * s2 * c2;
  const double w = rate_, k = p_.scale_m;
  ReferencePoint point;
  point.position = p_.center + k * Eigen::Vector2d(16 * s * s * s, 13 * c - 5 * c2 - 2 * c3 - c4);
  point.velocity = k * w * Eigen::Vector2d(48 * s * s * c, -13 * s + 10 * s2 + 6 * s3 + 4 * s4);
  point.acceleration =
      k * w * w * Eigen::Vector2d(48 * (2 * s * c * c - s * s * s), -13 * c + 20 * c2 + 18 * c3 + 16 * c4);
  return point;
}

double HeartTrajectory::duration_s() const { return p_.period_s; }

double HeartTrajectory::contour_error(const Eigen::Vector2d& point) const {
  const FootPoint foot = exact_foot_point(*this, point);
  // Inside/outside by the winding of the closed curve around the point (even-odd crossings).
  bool inside = false;
  const int n = 720;
  Eigen::Vector2d previous = sample(0.0).position;
  for (int i = 1; i <= n; ++i) {
    const Eigen::Vector2d current = sample(p_.period_s * i / n).position;
    if ((current.y() > point.y()) != (previous.y() > point.y())) {
      const double x = previous.x() + (point.y() - previous.y()) * (current.x() - previous.x()) /
                                          (current.y() - previous.y());
      if (point.x() < x) inside = !inside;
    }
    previous = current;
  }
  return inside ? -foot.distance_m : foot.distance_m;
}

std::unique_ptr<ReferenceTrajectory> HeartTrajectory::clone() const {
  return std::make_unique<HeartTrajectory>(*this);
}

std::string HeartTrajectory::describe() const {
  std::ostringstream text;
  text << "heart(scale=" << p_.scale_m * 1e3 << " mm, centre=(" << p_.center.x() * 1e3 << ", "
       << p_.center.y() * 1e3 << ") mm, period=" << p_.period_s << " s)";
  return text.str();
}

}  // namespace netmc::control
