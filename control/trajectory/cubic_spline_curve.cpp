#include "control/trajectory/cubic_spline_curve.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {

CubicSplineCurve::CubicSplineCurve(std::vector<Eigen::Vector2d> points) : points_(std::move(points)) {
  if (points_.size() < 2) {
    throw std::invalid_argument("spline points: expected at least two points, got " +
                                std::to_string(points_.size()));
  }
  knots_.assign(1, 0.0);
  for (std::size_t i = 0; i < points_.size(); ++i) {
    require_finite(points_[i].x(), "spline point x");
    require_finite(points_[i].y(), "spline point y");
    if (i == 0) continue;
    const double chord = (points_[i] - points_[i - 1]).norm();
    if (!(chord > 0.0)) {
      throw std::invalid_argument("spline points: point " + std::to_string(i + 1) + " repeats point " +
                                  std::to_string(i) + " (consecutive points must differ)");
    }
    knots_.push_back(knots_.back() + chord);
  }
  closed_ = points_.size() > 2 && points_.back() == points_.front();
  if (closed_ && points_.size() < 4) {
    throw std::invalid_argument("spline points: a closed spline needs at least three distinct points");
  }
  // Continuity of the second derivative at the knots: for knot i with spans h0 = h_{i-1}, h1 = h_i,
  // h0 M_{i-1} + 2 (h0 + h1) M_i + h1 M_{i+1} = 6 ((P_{i+1} - P_i)/h1 - (P_i - P_{i-1})/h0).
  const int n = static_cast<int>(points_.size()) - 1;  // spans
  const auto h = [&](int i) { return knots_[static_cast<std::size_t>(i + 1)] - knots_[static_cast<std::size_t>(i)]; };
  const auto p = [&](int i) { return points_[static_cast<std::size_t>(i)]; };
  curvatures_.assign(points_.size(), Eigen::Vector2d::Zero());
  if (closed_) {
    // Periodic: unknowns M_0..M_{n-1}, M_n = M_0.
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd b(n, 2);
    for (int i = 0; i < n; ++i) {
      const int previous = (i + n - 1) % n;
      const double h0 = h(previous), h1 = h(i);
      a(i, previous) += h0;
      a(i, i) += 2 * (h0 + h1);
      a(i, (i + 1) % n) += h1;
      b.row(i) = (6.0 * ((p(i + 1) - p(i)) / h1 - (p(i) - p(previous)) / h0)).transpose();
    }
    const Eigen::MatrixXd m = a.partialPivLu().solve(b);
    for (int i = 0; i < n; ++i) curvatures_[static_cast<std::size_t>(i)] = m.row(i).transpose();
    curvatures_.back() = curvatures_.front();
  } else if (n >= 2) {
    // Natural: M_0 = M_n = 0, unknowns M_1..M_{n-1}.
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n - 1, n - 1);
    Eigen::MatrixXd b(n - 1, 2);
    for (int i = 1; i < n; ++i) {
      const double h0 = h(i - 1), h1 = h(i);
      if (i > 1) a(i - 1, i - 2) = h0;
      a(i - 1, i - 1) = 2 * (h0 + h1);
      if (i < n - 1) a(i - 1, i) = h1;
      b.row(i - 1) = (6.0 * ((p(i + 1) - p(i)) / h1 - (p(i) - p(i - 1)) / h0)).transpose();
    }
    const Eigen::MatrixXd m = a.partialPivLu().solve(b);
    for (int i = 1; i < n; ++i) curvatures_[static_cast<std::size_t>(i)] = m.row(i - 1).transpose();
  }
}

CurvePoint CubicSplineCurve::evaluate(double u) const {
  u = std::clamp(u, 0.0, span());
  const auto after = std::upper_bound(knots_.begin(), knots_.end(), u);
  const std::size_t i = std::min(static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - knots_.begin() - 1, 0)),
                                 points_.size() - 2);
  const double h = knots_[i + 1] - knots_[i];
  const double left = knots_[i + 1] - u, right = u - knots_[i];
  const Eigen::Vector2d& m0 = curvatures_[i];
  const Eigen::Vector2d& m1 = curvatures_[i + 1];
  const Eigen::Vector2d c0 = points_[i] / h - m0 * h / 6.0;
  const Eigen::Vector2d c1 = points_[i + 1] / h - m1 * h / 6.0;
  CurvePoint c;
  c.position = m0 * (left * left * left) / (6 * h) + m1 * (right * right * right) / (6 * h) + c0 * left + c1 * right;
  c.first = -m0 * (left * left) / (2 * h) + m1 * (right * right) / (2 * h) - c0 + c1;
  c.second = m0 * left / h + m1 * right / h;
  return c;
}

std::string CubicSplineCurve::describe() const {
  std::ostringstream text;
  text << "cubic spline through " << points_.size() << " points" << (closed_ ? ", closed" : "");
  return text.str();
}

}  // namespace netmc::control
