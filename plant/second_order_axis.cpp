#include "plant/second_order_axis.hpp"

#include <cmath>
#include <sstream>
#include <utility>

#include "plant/coulomb_taylor_step.hpp"
#include "plant/parameter_checks.hpp"
#include "plant/rk4_integrator.hpp"
#include "plant/smooth_sign.hpp"

namespace netmc::plant {
namespace {

constexpr const char* kSecondOrderAxisOwner = "SecondOrderAxis";

SecondOrderAxisParameters validated(SecondOrderAxisParameters p) {
  require_finite(kSecondOrderAxisOwner, "a1", p.a1);
  require_finite(kSecondOrderAxisOwner, "a2", p.a2);
  require_finite(kSecondOrderAxisOwner, "b", p.b);
  require_non_negative(kSecondOrderAxisOwner, "coulomb_acceleration", p.coulomb_acceleration);
  require_positive(kSecondOrderAxisOwner, "coulomb_velocity_scale", p.coulomb_velocity_scale);
  validate_disturbance(p.disturbance, kSecondOrderAxisOwner);
  require_positive(kSecondOrderAxisOwner, "max_substep_s", p.max_substep_s);
  return p;
}

}  // namespace

SecondOrderAxis::SecondOrderAxis(SecondOrderAxisParameters p)
    : TwoStateAxisPlant(kSecondOrderAxisOwner), p_(validated(std::move(p))) {
  // Paper 001, eq. 3 in state form z = [x1, x2]: x1' = x2, x2' = a1 x1 + a2 x2 + w, with the held
  // input w = b u + d entering the velocity equation.
  Eigen::Matrix2d a;
  a << 0.0, 1.0, p_.a1, p_.a2;
  exact_ = ExactDiscretizer(a, Eigen::Vector2d(0.0, 1.0));
}

void SecondOrderAxis::advance_piece(double t0, double duration, double input, double step_level) {
  const Disturbance& d = p_.disturbance;
  if (p_.coulomb_acceleration == 0.0 && smooth_part_is_constant(d)) {
    // Linear with a held input: exact (netmc's choice [A], exact_discretizer.hpp).
    exact_.step(state(), duration, p_.b * input + smooth_part(d, t0) + step_level);
    return;
  }
  const double forcing = p_.b * input + step_level;
  const double c = p_.coulomb_acceleration;
  const double inv_scale = 1.0 / p_.coulomb_velocity_scale;
  const double a1 = p_.a1;
  const double a2 = p_.a2;
  const long long n = substep_count(kSecondOrderAxisOwner, duration, p_.max_substep_s);
  double x = state()(0);
  double v = state()(1);
  // Paper 001, eq. 3 with netmc's assumed friction [A] -c tanh(x'/scale).
  if (smooth_part_is_constant(d)) {
    const double w = forcing + smooth_part(d, t0);
    const CoulombAxisCoefficients k{a1, a2, w, c, inv_scale};
    const double h = duration / static_cast<double>(n);
    // Fifth-order Taylor steps (one tanh each); RK4 where the friction's argument moves too far.
    for (long long i = 0; i < n; ++i) {
      if (coulomb_taylor_step(x, v, h, k)) continue;
      rk4_second_order(x, v, t0 + static_cast<double>(i) * h, h, 1, [&](double, double xx, double vv) {
        return a1 * xx + a2 * vv + w - c * smooth_sign(vv * inv_scale);
      });
    }
  } else {
    rk4_second_order(x, v, t0, duration, n, [&](double t, double xx, double vv) {
      return a1 * xx + a2 * vv + forcing + smooth_part(d, t) - c * smooth_sign(vv * inv_scale);
    });
  }
  state() << x, v;
}

std::unique_ptr<AxisPlant> SecondOrderAxis::clone() const {
  return std::make_unique<SecondOrderAxis>(*this);
}

std::string SecondOrderAxis::describe() const {
  std::ostringstream out;
  out << "SecondOrderAxis (paper 001 eq. 3): a1=" << p_.a1 << " 1/s^2, a2=" << p_.a2
      << " 1/s, b=" << p_.b << ", coulomb=" << p_.coulomb_acceleration << " m/s^2 (scale "
      << p_.coulomb_velocity_scale << " m/s), d=" << describe_disturbance(p_.disturbance, "m/s^2")
      << ", max_substep=" << p_.max_substep_s << " s";
  return out.str();
}

}  // namespace netmc::plant
