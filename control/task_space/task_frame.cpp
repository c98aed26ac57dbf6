#include "control/task_space/task_frame.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/trajectory/ellipse_trajectory.hpp"
#include "control/trajectory/foot_point.hpp"
#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

constexpr int kArcTableSize = 8192;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

double wrap_angle(double angle) {
  const double wrapped = std::fmod(angle, kTwoPi);
  return wrapped < 0.0 ? wrapped + kTwoPi : wrapped;
}

// Linear interpolation in a table sampled uniformly over [0, span].
double interpolate(const std::vector<double>& table, double span, double x) {
  const double position = std::clamp(x / span, 0.0, 1.0) * static_cast<double>(table.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(position), table.size() - 2);
  const double f = position - static_cast<double>(i);
  return table[i] + f * (table[i + 1] - table[i]);
}

// Cumulative arc length of a speed function sampled on a uniform grid (trapezoid rule).
template <typename Speed>
std::vector<double> arc_table(double span, Speed&& speed) {
  std::vector<double> table(kArcTableSize + 1, 0.0);
  const double step = span / kArcTableSize;
  double previous = speed(0.0);
  for (int i = 1; i <= kArcTableSize; ++i) {
    const double current = speed(step * i);
    table[static_cast<std::size_t>(i)] = table[static_cast<std::size_t>(i - 1)] + 0.5 * step * (previous + current);
    previous = current;
  }
  return table;
}

}  // namespace

CircleTaskFrame::CircleTaskFrame(const Eigen::Vector2d& center, double radius, bool clockwise)
    : center_(center), radius_(require_positive(radius, "circle r")), clockwise_(clockwise) {}

double CircleTaskFrame::perimeter_m() const { return kTwoPi * radius_; }

TaskCoordinates CircleTaskFrame::at(const Eigen::Vector2d& q) const {
  // thesis, eq. 2-34..2-36 (J derived from them for a centre (x0, y0))
  const Eigen::Vector2d d = q - center_;
  const double rho = d.norm();
  if (rho <= 0.0) throw std::invalid_argument("circle task frame: undefined at the centre");
  TaskCoordinates r;
  r.rc = rho - radius_;
  const double angle = std::atan2(d.y(), d.x());
  r.rm = radius_ * wrap_angle(clockwise_ ? -angle : angle);
  const double along = clockwise_ ? -radius_ : radius_;
  r.jacobian << d.x() / rho, d.y() / rho, -along * d.y() / (rho * rho), along * d.x() / (rho * rho);
  return r;
}

EllipseTaskFrame::EllipseTaskFrame(const Eigen::Vector2d& center, double semi_axis_x,
                                   double semi_axis_y)
    : center_(center),
      a_(require_positive(semi_axis_x, "ellipse a")),
      b_(require_positive(semi_axis_y, "ellipse b")) {
  arc_table_ = arc_table(kTwoPi, [&](double nu) {
    return std::sqrt(a_ * a_ * std::sin(nu) * std::sin(nu) + b_ * b_ * std::cos(nu) * std::cos(nu));
  });
}

double EllipseTaskFrame::arc_length(double nu) const { return interpolate(arc_table_, kTwoPi, wrap_angle(nu)); }

double EllipseTaskFrame::rc(const Eigen::Vector2d& p) const {
  // thesis, eq. 2-42: rc = sqrt(g2)/sqrt(h2) (sqrt(g2) - b), g2 = gamma^2 x^2 + y^2,
  // h2 = gamma^4 x^2 + y^2, gamma = b/a
  const double gamma2 = (b_ / a_) * (b_ / a_);
  const double g = std::sqrt(gamma2 * p.x() * p.x() + p.y() * p.y());
  const double h = std::sqrt(gamma2 * gamma2 * p.x() * p.x() + p.y() * p.y());
  return g / h * (g - b_);
}

double EllipseTaskFrame::parameter(const Eigen::Vector2d& p) const {
  // thesis, eq. 2-21: project along grad f onto the contour (f = u - 1, u^2 = x^2/a^2 + y^2/b^2),
  // then the arc length of the projected point's parameter (netmc's assumption [A]: branch by atan2,
  // since eq. 2-42's arccos covers half the ellipse).
  const double u = std::sqrt(p.x() * p.x() / (a_ * a_) + p.y() * p.y() / (b_ * b_));
  const Eigen::Vector2d grad(p.x() / (a_ * a_ * u), p.y() / (b_ * b_ * u));
  const Eigen::Vector2d projected = p - (u - 1.0) * grad / grad.squaredNorm();
  return std::atan2(projected.y() / b_, projected.x() / a_);
}

TaskCoordinates EllipseTaskFrame::at(const Eigen::Vector2d& q) const {
  const Eigen::Vector2d p = q - center_;
  if (p.norm() <= 0.0) throw std::invalid_argument("ellipse task frame: undefined at the centre");
  TaskCoordinates r;
  r.rc = rc(p);
  const double nu = parameter(p);
  r.rm = arc_length(nu);
  // grad rc, analytic: rc = N / h with N = g^2 - b g.
  const double gamma2 = (b_ / a_) * (b_ / a_);
  const double g = std::sqrt(gamma2 * p.x() * p.x() + p.y() * p.y());
  const double h = std::sqrt(gamma2 * gamma2 * p.x() * p.x() + p.y() * p.y());
  const double n = g * g - b_ * g;
  const Eigen::Vector2d grad_n(2 * gamma2 * p.x() - b_ * gamma2 * p.x() / g, 2 * p.y() - b_ * p.y() / g);
  const Eigen::Vector2d grad_h(gamma2 * gamma2 * p.x() / h, p.y() / h);
  const Eigen::Vector2d grad_rc = (grad_n * h - n * grad_h) / (h * h);
  // grad rm = s'(nu) grad nu: s' analytic, grad nu by central differences across the seam.
  const double step = 1e-7 * std::max(a_, b_);
  const auto difference = [&](const Eigen::Vector2d& offset) {
    return std::remainder(parameter(p + offset) - parameter(p - offset), kTwoPi) / (2.0 * step);
  };
  const double speed = std::sqrt(a_ * a_ * std::sin(nu) * std::sin(nu) + b_ * b_ * std::cos(nu) * std::cos(nu));
  r.jacobian.row(0) = grad_rc.transpose();
  r.jacobian.row(1) << speed * difference({step, 0.0}), speed * difference({0.0, step});
  return r;
}

NumericalTaskFrame::NumericalTaskFrame(std::shared_ptr<const ReferenceTrajectory> contour)
    : contour_(std::move(contour)) {
  if (!contour_) throw std::invalid_argument("task frame: missing contour");
  arc_table_ = arc_table(contour_->duration_s(),
                         [&](double t) { return contour_->sample(t).velocity.norm(); });
  grid_ = sample_contour(*contour_);
}

double NumericalTaskFrame::perimeter_m() const {
  const double gap = (contour_->sample(contour_->duration_s()).position - contour_->sample(0.0).position).norm();
  return gap < 1e-9 ? arc_table_.back() : 0.0;
}

TaskCoordinates NumericalTaskFrame::at(const Eigen::Vector2d& q) const {
  return coordinates(q, nearest_on_contour(grid_, curve_of(*contour_), q));
}

std::size_t NumericalTaskFrame::sample_index(double rm) const {
  const auto entry = std::lower_bound(arc_table_.begin(), arc_table_.end(), rm);
  const double fraction = static_cast<double>(entry - arc_table_.begin()) / static_cast<double>(arc_table_.size() - 1);
  return static_cast<std::size_t>(std::lround(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(grid_.positions.size() - 1)));
}

TaskCoordinates NumericalTaskFrame::near(const Eigen::Vector2d& q, double rm_hint) const {
  const double length = arc_table_.back();
  const double window = 0.05 * length;
  const double perimeter = perimeter_m();
  if (perimeter > 0.0) {
    // Closed: the window may run across the seam.
    const auto wrap = [&](double rm) { return rm - perimeter * std::floor(rm / perimeter); };
    return coordinates(q, nearest_on_contour(grid_, curve_of(*contour_), q, sample_index(wrap(rm_hint - window)),
                                             sample_index(wrap(rm_hint + window))));
  }
  return coordinates(q, nearest_on_contour(grid_, curve_of(*contour_), q, sample_index(rm_hint - window),
                                           sample_index(rm_hint + window)));
}

TaskCoordinates NumericalTaskFrame::coordinates(const Eigen::Vector2d& q, const FootPoint& foot) const {
  const ReferencePoint c = contour_->sample(foot.time_s);
  const double mean_speed = arc_table_.back() / contour_->duration_s();
  TaskCoordinates r;
  r.rm = interpolate(arc_table_, contour_->duration_s(), foot.time_s);
  if (c.velocity.norm() > 1e-6 * mean_speed) {
    const Eigen::Vector2d tangent = c.velocity.normalized();
    const Eigen::Vector2d normal(tangent.y(), -tangent.x());  // right of travel
    r.rc = (q - c.position).dot(normal) >= 0.0 ? foot.distance_m : -foot.distance_m;
    r.jacobian.row(0) = normal.transpose();
    r.jacobian.row(1) = tangent.transpose();
    return r;
  }
  // The motion stops at the foot point (a sharp corner): the side by the chord through it, and
  // the gradient of the distance, (q - c) / |q - c|, as the contour direction.
  const double step = 1e-6 * contour_->duration_s();
  const Eigen::Vector2d chord = contour_->sample(std::min(foot.time_s + step, contour_->duration_s())).position -
                                contour_->sample(std::max(foot.time_s - step, 0.0)).position;
  if (!(chord.norm() > 0.0)) throw std::invalid_argument("task frame: the foot point is a cusp (no tangent)");
  Eigen::Vector2d normal = Eigen::Vector2d(chord.y(), -chord.x()).normalized();
  const Eigen::Vector2d offset = q - c.position;
  const bool right = offset.dot(normal) >= 0.0;
  if (foot.distance_m > 0.0) normal = (right ? offset : -offset) / foot.distance_m;
  r.rc = right ? foot.distance_m : -foot.distance_m;
  r.jacobian.row(0) = normal.transpose();
  r.jacobian.row(1) << -normal.y(), normal.x();
  return r;
}

std::shared_ptr<const TaskFrame> make_task_frame(const ReferenceTrajectory& motion) {
  const ReferenceTrajectory& trajectory = motion.geometry();
  if (const auto* circle = dynamic_cast<const CircleTrajectory*>(&trajectory)) {
    const auto& p = circle->parameters();
    return std::make_shared<CircleTaskFrame>(p.center, p.radius_m, p.clockwise);
  }
  if (const auto* ellipse = dynamic_cast<const EllipseTrajectory*>(&trajectory); ellipse && !ellipse->parameters().clockwise) {
    const auto& p = ellipse->parameters();
    return std::make_shared<EllipseTaskFrame>(p.center, p.semi_axis_x_m, p.semi_axis_y_m);
  }
  return std::make_shared<NumericalTaskFrame>(std::shared_ptr<const ReferenceTrajectory>(trajectory.clone()));
}

}  // namespace netmc::control
