#pragma once
// Independent closed-form solutions used as ground truth by the plant tests.

#include <cmath>
#include <numbers>

namespace netmc::plant::test {

struct Motion {
  double x = 0.0;
  double v = 0.0;
};

// x'' = a x' + w (a != 0, w constant) from (x0, v0):
//   v(t) = v0 e^{a t} + (w/a)(e^{a t} - 1)
//   x(t) = x0 + v0 (e^{a t} - 1)/a + (w/a^2)(e^{a t} - 1) - w t / a
inline Motion damped_axis_step(double a, double w, double x0, double v0, double t) {
  const double em1 = std::expm1(a * t);
  return {x0 + v0 * em1 / a + w / (a * a) * em1 - w * t / a, v0 * (em1 + 1.0) + w / a * em1};
}

// x'' = a x' + A sin(om t + ph) from rest (a != 0). Particular velocity
// v_p = alpha sin(om t + ph) + beta cos(om t + ph), alpha = -A a/(om^2 + a^2),
// beta = -A om/(om^2 + a^2); v = v_p(t) - v_p(0) e^{a t}; x = integral of v.
inline Motion damped_axis_sine(double a, double amp, double om, double ph, double t) {
  const double den = om * om + a * a;
  const double alpha = -amp * a / den;
  const double beta = -amp * om / den;
  auto vp = [&](double s) { return alpha * std::sin(om * s + ph) + beta * std::cos(om * s + ph); };
  auto xp = [&](double s) {  // antiderivative of v_p
    return -alpha / om * std::cos(om * s + ph) + beta / om * std::sin(om * s + ph);
  };
  const double em1 = std::expm1(a * t);
  return {xp(t) - xp(0.0) - vp(0.0) * em1 / a, vp(t) - vp(0.0) * (em1 + 1.0)};
}

// q'' + 2 z w q' + w^2 q = k F from rest, F constant, 0 <= z < 1:
//   q(t) = kF/w^2 [1 - e^{-z w t}(cos(wd t) + z/sqrt(1-z^2) sin(wd t))], wd = w sqrt(1-z^2)
inline Motion mode_step(double k, double z, double w, double force, double t) {
  const double r = std::sqrt(1.0 - z * z);
  const double wd = w * r;
  const double e = std::exp(-z * w * t);
  const double s = k * force / (w * w);
  const double q = s * (1.0 - e * (std::cos(wd * t) + z / r * std::sin(wd * t)));
  const double qd = s * e * (w / r) * std::sin(wd * t);
  return {q, qd};
}

inline double relative_error(double value, double truth) {
  return std::abs(value - truth) / std::abs(truth);
}

}  // namespace netmc::plant::test
