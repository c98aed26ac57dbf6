#include "control/trajectory/lissajous_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

LissajousCurve::LissajousCurve(const LissajousParameters& parameters) : p_(parameters) {
  require_finite(p_.center.x(), "lissajous cx");
  require_finite(p_.center.y(), "lissajous cy");
  require_positive(p_.amplitude_x_m, "lissajous ax");
  require_positive(p_.amplitude_y_m, "lissajous ay");
  require_finite(p_.phase_rad, "lissajous phase");
  if (p_.frequency_x < 1 || p_.frequency_y < 1) {
    throw std::invalid_argument("lissajous p, q: expected positive whole numbers, got p=" +
                                std::to_string(p_.frequency_x) + ", q=" + std::to_string(p_.frequency_y));
  }
  // With both cosines vanishing together the figure stops and retraces itself (p = q = 1 at
  // phase 0 is a line run back and forth): no tangent there, so no contour frame.
  double slowest = std::numeric_limits<double>::infinity(), fastest = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double speed = evaluate(span() * i / 20000.0).first.norm();
    slowest = std::min(slowest, speed);
    fastest = std::max(fastest, speed);
  }
  if (slowest < 1e-3 * fastest) {
    throw std::invalid_argument(
        "lissajous: the figure stops and retraces itself for these p, q and phase (choose p, q "
        "of different parity, or a phase other than a multiple of pi/2)");
  }
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

LissajousTrajectory::LissajousTrajectory(const LissajousParameters& parameters)
    : curve_(parameters), period_s_(require_positive(parameters.period_s, "lissajous period")) {
  rate_ = curve_.span() / period_s_;
  grid_ = sample_contour([this](double u) { return curve_.evaluate(u).position; }, curve_.span());
}

ReferencePoint LissajousTrajectory::sample(double time_s) const {
  // u = w t: the chain rule scales the derivatives by w and w^2.
  const CurvePoint c = curve_.evaluate(rate_ * time_s);
  return {c.position, rate_ * c.first, rate_ * rate_ * c.second};
}

double LissajousTrajectory::contour_error(const Eigen::Vector2d& point) const {
  const FootPoint foot = nearest_on_contour(grid_, [this](double u) { return curve_.evaluate(u); }, point);
  const CurvePoint c = curve_.evaluate(foot.time_s);
  const Eigen::Vector2d right(c.first.y(), -c.first.x());
  return (point - c.position).dot(right) >= 0.0 ? foot.distance_m : -foot.distance_m;
}

std::unique_ptr<ReferenceTrajectory> LissajousTrajectory::clone() const {
  return std::make_unique<LissajousTrajectory>(*this);
}

std::string LissajousTrajectory::describe() const {
  std::ostringstream text;
  text << curve_.describe() << ", period=" << period_s_ << " s";
  return text.str();
}

}  // namespace netmc::control
