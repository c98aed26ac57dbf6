#include "control/trajectory/feed_rate_trajectory.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

// Five-point Gauss-Legendre rule on [-1, 1].
constexpr std::array<double, 5> kGaussNodes{0.0, -0.5384693101056831, 0.5384693101056831,
                                            -0.9061798459386640, 0.9061798459386640};
constexpr std::array<double, 5> kGaussWeights{0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                              0.2369268850561891, 0.2369268850561891};

double arc_between(const PlanarCurve& curve, double u0, double u1) {
  const double half = 0.5 * (u1 - u0), middle = 0.5 * (u0 + u1);
  double sum = 0.0;
  for (std::size_t k = 0; k < kGaussNodes.size(); ++k) {
    sum += kGaussWeights[k] * curve.evaluate(middle + half * kGaussNodes[k]).first.norm();
  }
  return half * sum;
}

}  // namespace

FeedRateTrajectory::FeedRateTrajectory(std::shared_ptr<const PlanarCurve> curve,
                                       const FeedRateLimits& limits, int intervals)
    : curve_(std::move(curve)), limits_(limits) {
  if (!curve_) throw std::invalid_argument("feed-rate trajectory: missing curve");
  require_positive(limits_.feed_m_s, "feed");
  require_positive(limits_.normal_acceleration_m_s2, "normal acceleration limit");
  require_positive(limits_.tangential_acceleration_m_s2, "tangential acceleration limit");
  const int n = intervals > 0 ? intervals : std::max(4096, 64 * curve_->pieces());
  const auto size = static_cast<std::size_t>(n) + 1;
  step_u_ = curve_->span() / n;
  arcs_.assign(size, 0.0);
  std::vector<double> limit(size, limits_.feed_m_s);
  for (std::size_t i = 0; i < size; ++i) {
    const double u = step_u_ * static_cast<double>(i);
    if (i > 0) arcs_[i] = arcs_[i - 1] + arc_between(*curve_, u - step_u_, u);
    // The sharpest bend at the point and half a step either side, to stay within the limit
    // between the table points too.
    double curvature = 0.0;
    for (double offset : {-0.5 * step_u_, 0.0, 0.5 * step_u_}) {
      const CurvePoint c = curve_->evaluate(std::clamp(u + offset, 0.0, curve_->span()));
      if (!(c.first.norm() > 0.0)) {
        throw std::invalid_argument("feed-rate trajectory: the curve has a point without tangent");
      }
      curvature = std::max(curvature, std::abs(signed_curvature(c)));
    }
    if (curvature > 0.0) limit[i] = std::min(limit[i], std::sqrt(limits_.normal_acceleration_m_s2 / curvature));
  }
  // From rest to rest: forward pass (accelerating), backward pass (braking), both limited by
  // v_{i+1}^2 <= v_i^2 + 2 a_t ds.
  const double a = limits_.tangential_acceleration_m_s2;
  speeds_ = limit;
  speeds_.front() = speeds_.back() = 0.0;
  for (std::size_t i = 1; i < size; ++i) {
    const double ds = arcs_[i] - arcs_[i - 1];
    speeds_[i] = std::min(speeds_[i], std::sqrt(speeds_[i - 1] * speeds_[i - 1] + 2 * a * ds));
  }
  for (std::size_t i = size - 1; i-- > 0;) {
    const double ds = arcs_[i + 1] - arcs_[i];
    speeds_[i] = std::min(speeds_[i], std::sqrt(speeds_[i + 1] * speeds_[i + 1] + 2 * a * ds));
  }
  times_.assign(size, 0.0);
  for (std::size_t i = 1; i < size; ++i) {
    times_[i] = times_[i - 1] + 2.0 * (arcs_[i] - arcs_[i - 1]) / (speeds_[i - 1] + speeds_[i]);
  }
  grid_ = sample_contour([this](double u) { return curve_->evaluate(u).position; }, curve_->span());
  double area2 = 0.0;
  for (std::size_t i = 1; i < grid_.positions.size(); ++i) {
    const Eigen::Vector2d& p0 = grid_.positions[i - 1];
    const Eigen::Vector2d& p1 = grid_.positions[i];
    area2 += p0.x() * p1.y() - p1.x() * p0.y();
  }
  orientation_ = curve_->closed() && !curve_->self_intersecting() && area2 < 0.0 ? -1.0 : 1.0;
}

std::size_t FeedRateTrajectory::interval_of_parameter(double u) const {
  const auto i = static_cast<std::size_t>(std::max(0.0, std::floor(u / step_u_)));
  return std::min(i, arcs_.size() - 2);
}

double FeedRateTrajectory::arc_length(double u) const {
  u = std::clamp(u, 0.0, curve_->span());
  const std::size_t i = interval_of_parameter(u);
  return arcs_[i] + arc_between(*curve_, step_u_ * static_cast<double>(i), u);
}

double FeedRateTrajectory::parameter_at(double s, std::size_t i) const {
  const double u0 = step_u_ * static_cast<double>(i);
  const double ds = arcs_[i + 1] - arcs_[i];
  double u = u0 + step_u_ * std::clamp((s - arcs_[i]) / ds, 0.0, 1.0);
  // Newton on arc_length(u) = s: its derivative is the speed |C'(u)|.
  for (int k = 0; k < 6; ++k) {
    const double residual = arcs_[i] + arc_between(*curve_, u0, u) - s;
    const double update = residual / curve_->evaluate(u).first.norm();
    u -= update;
    if (std::abs(update) < 1e-15 * curve_->span()) break;
  }
  return u;
}

ReferencePoint FeedRateTrajectory::sample(double time_s) const {
  const double t = std::clamp(time_s, 0.0, duration_s());
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  const auto i = std::min(static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - times_.begin() - 1, 0)),
                          times_.size() - 2);
  // Constant tangential acceleration on the interval.
  const double ds = arcs_[i + 1] - arcs_[i];
  const double v0 = speeds_[i], v1 = speeds_[i + 1];
  const double acceleration = (v1 * v1 - v0 * v0) / (2.0 * ds);
  const double tau = t - times_[i];
  const double s = std::min(arcs_[i] + v0 * tau + 0.5 * acceleration * tau * tau, arcs_[i + 1]);
  const double speed = std::max(0.0, v0 + acceleration * tau);
  const CurvePoint c = curve_->evaluate(parameter_at(s, i));
  // Chain rule through the arc-length parameter: du/ds = 1/|C'|, d2u/ds2 = -(C'.C'')/|C'|^4.
  const double sigma = c.first.norm();
  const double du_ds = 1.0 / sigma;
  const double d2u_ds2 = -c.first.dot(c.second) / (sigma * sigma * sigma * sigma);
  const Eigen::Vector2d tangent = c.first * du_ds;
  const Eigen::Vector2d bend = c.second * du_ds * du_ds + c.first * d2u_ds2;
  ReferencePoint point;
  point.position = c.position;
  point.velocity = tangent * speed;
  point.acceleration = bend * speed * speed + tangent * acceleration;
  return point;
}

double FeedRateTrajectory::contour_error(const Eigen::Vector2d& point) const {
  const FootPoint foot =
      nearest_on_contour(grid_, [this](double u) { return curve_->evaluate(u); }, point);
  const CurvePoint c = curve_->evaluate(foot.time_s);
  const Eigen::Vector2d right(c.first.y(), -c.first.x());
  return orientation_ * ((point - c.position).dot(right) >= 0.0 ? foot.distance_m : -foot.distance_m);
}

std::unique_ptr<ReferenceTrajectory> FeedRateTrajectory::clone() const {
  return std::make_unique<FeedRateTrajectory>(*this);
}

std::string FeedRateTrajectory::describe() const {
  std::ostringstream text;
  text << curve_->describe() << ", length=" << length_m() * 1e3 << " mm, feed=" << limits_.feed_m_s * 1e3
       << " mm/s, v^2 kappa <= " << limits_.normal_acceleration_m_s2 * 1e3
       << " mm/s^2, |a_t| <= " << limits_.tangential_acceleration_m_s2 * 1e3 << " mm/s^2, "
       << duration_s() << " s";
  return text.str();
}

}  // namespace netmc::control
