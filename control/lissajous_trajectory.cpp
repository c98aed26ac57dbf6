#include "control/lissajous_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

LissajousTrajectory::LissajousTrajectory(const LissajousParameters& parameters) : p_(parameters) {
  require_finite(p_.center.x(), "lissajous cx");
  require_finite(p_.center.y(), "lissajous cy");
  require_positive(p_.amplitude_x_m, "lissajous ax");
  require_positive(p_.amplitude_y_m, "lissajous ay");
  require_finite(p_.phase_rad, "lissajous phase");
  require_positive(p_.period_s, "lissajous period");
  if (p_.frequency_x < 1 || p_.frequency_y < 1) {
    throw std::invalid_argument("lissajous p, q: expected positive whole numbers, got p=" +
                                std::to_string(p_.frequency_x) + ", q=" + std::to_string(p_.frequency_y));
  }
  rate_ = 2.0 * std::numbers::pi / p_.period_s;
  // With both cosines vanishing together the figure stops and retraces itself (p = q = 1 at
  // phase 0 is a line run back and forth): no tangent there, so no contour frame.
  double slowest = std::numeric_limits<double>::infinity(), fastest = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double speed = sample(p_.period_s * i / 20000.0).velocity.norm();
    slowest = std::min(slowest, speed);
    fastest = std::max(fastest, speed);
  }
  if (slowest < 1e-3 * fastest) {
    throw std::invalid_argument(
        "lissajous: the figure stops and retraces itself for these p, q and phase (choose p, q "
        "of different parity, or a phase other than a multiple of pi/2)");
  }
  grid_ = sample_contour([this](double t) { return sample(t).position; }, p_.period_s);
}

ReferencePoint LissajousTrajectory::sample(double time_s) const {
  const double wx = p_.frequency_x * rate_;
  const double wy = p_.frequency_y * rate_;
  const double ax = p_.amplitude_x_m, ay = p_.amplitude_y_m;
  const double fx = wx * time_s + p_.phase_rad;
  const double fy = wy * time_s;
  ReferencePoint point;
  point.position = p_.center + Eigen::Vector2d(ax * std::sin(fx), ay * std::sin(fy));
  point.velocity = Eigen::Vector2d(ax * wx * std::cos(fx), ay * wy * std::cos(fy));
  point.acceleration = Eigen::Vector2d(-ax * wx * wx * std::sin(fx), -ay * wy * wy * std::sin(fy));
  return point;
}

double LissajousTrajectory::contour_error(const Eigen::Vector2d& point) const {
  const FootPoint foot = nearest_on_contour(grid_, curve_of(*this), point);
  const ReferencePoint c = sample(foot.time_s);
  const Eigen::Vector2d right(c.velocity.y(), -c.velocity.x());
  return (point - c.position).dot(right) >= 0.0 ? foot.distance_m : -foot.distance_m;
}

LissajousCurve::LissajousCurve(const LissajousParameters& parameters) : p_(parameters) {
  // Validation (and the retracing check) by the timed figure at unit period.
  LissajousParameters unit = p_;
  unit.period_s = 2.0 * std::numbers::pi;
  p_ = LissajousTrajectory(unit).parameters();
}

double LissajousCurve::span() const { return 2.0 * std::numbers::pi; }

CurvePoint LissajousCurve::evaluate(double u) const {
  const double px = p_.frequency_x, py = p_.frequency_y;
  const double ax = p_.amplitude_x_m, ay = p_.amplitude_y_m;
  const double fx = px * u + p_.phase_rad, fy = py * u;
  CurvePoint c;
  c.position = p_.center + Eigen::Vector2d(ax * std::sin(fx), ay * std::sin(fy));
  c.first = Eigen::Vector2d(ax * px * std::cos(fx), ay * py * std::cos(fy));
  c.second = Eigen::Vector2d(-ax * px * px * std::sin(fx), -ay * py * py * std::sin(fy));
  return c;
}

std::string LissajousCurve::describe() const {
  std::ostringstream text;
  text << "lissajous(ax=" << p_.amplitude_x_m * 1e3 << " mm, ay=" << p_.amplitude_y_m * 1e3
       << " mm, p=" << p_.frequency_x << ", q=" << p_.frequency_y << ", phase=" << p_.phase_rad
       << " rad, centre=(" << p_.center.x() * 1e3 << ", " << p_.center.y() * 1e3 << ") mm)";
  return text.str();
}

std::unique_ptr<ReferenceTrajectory> LissajousTrajectory::clone() const {
  return std::make_unique<LissajousTrajectory>(*this);
}

std::string LissajousTrajectory::describe() const {
  std::ostringstream text;
  text << "lissajous(ax=" << p_.amplitude_x_m * 1e3 << " mm, ay=" << p_.amplitude_y_m * 1e3
       << " mm, p=" << p_.frequency_x << ", q=" << p_.frequency_y << ", phase=" << p_.phase_rad
       << " rad, centre=(" << p_.center.x() * 1e3 << ", " << p_.center.y() * 1e3
       << ") mm, period=" << p_.period_s << " s)";
  return text.str();
}

}  // namespace netmc::control
