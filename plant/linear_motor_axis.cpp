#include "plant/linear_motor_axis.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "plant/smooth_sign.hpp"

#include "plant/parameter_checks.hpp"
#include "plant/rk4_integrator.hpp"

namespace netmc::plant {
namespace {

constexpr const char* kLinearMotorAxisOwner = "LinearMotorAxis";

LinearMotorParameters validated(LinearMotorParameters p) {
  require_positive(kLinearMotorAxisOwner, "mass", p.mass);
  require_non_negative(kLinearMotorAxisOwner, "damping", p.damping);
  require_non_negative(kLinearMotorAxisOwner, "coulomb", p.coulomb);
  require_non_negative(kLinearMotorAxisOwner, "stribeck_extra", p.stribeck_extra);
  require_positive(kLinearMotorAxisOwner, "stribeck_velocity", p.stribeck_velocity);
  require_positive(kLinearMotorAxisOwner, "friction_smoothing_velocity", p.friction_smoothing_velocity);
  require_positive(kLinearMotorAxisOwner, "cogging_pitch_m", p.cogging_pitch_m);
  for (std::size_t i = 0; i < p.cogging.size(); ++i) {
    const std::string name = "cogging[" + std::to_string(i) + "]";
    require_finite(kLinearMotorAxisOwner, name + ".sine", p.cogging[i].sine);
    require_finite(kLinearMotorAxisOwner, name + ".cosine", p.cogging[i].cosine);
    if (p.cogging[i].order < 1) {
      throw std::invalid_argument(std::string(kLinearMotorAxisOwner) + ": " + name +
                                  ".order must be an integer >= 1 (got " +
                                  std::to_string(p.cogging[i].order) + ")");
    }
  }
  validate_disturbance(p.disturbance, kLinearMotorAxisOwner);
  require_positive(kLinearMotorAxisOwner, "max_substep_s", p.max_substep_s);
  return p;
}

}  // namespace

LinearMotorAxis::LinearMotorAxis(LinearMotorParameters p)
    : TwoStateAxisPlant(kLinearMotorAxisOwner), p_(validated(std::move(p))) {
  bool cogging_off = true;
  wavenumbers_.reserve(p_.cogging.size());
  for (const CoggingHarmonic& h : p_.cogging) {
    // Paper 000, eq. 4-2: harmonic i has spatial frequency 2 i pi / P.
    wavenumbers_.push_back(2.0 * std::numbers::pi * h.order / p_.cogging_pitch_m);
    if (h.sine != 0.0 || h.cosine != 0.0) cogging_off = false;
  }
  linear_ = cogging_off && p_.coulomb == 0.0 && p_.stribeck_extra == 0.0;
  // Linear part: y'' = -(B/M) y' + (u + d)/M.
  Eigen::Matrix2d a;
  a << 0.0, 1.0, 0.0, -p_.damping / p_.mass;
  exact_ = ExactDiscretizer(a, Eigen::Vector2d(0.0, 1.0 / p_.mass));
}

double LinearMotorAxis::friction_force(double velocity) const {
  // Paper 000, eq. A.3 (Stribeck, xi = 2), sign chosen to oppose motion (as printed it would aid it).
  double level = p_.coulomb;
  if (p_.stribeck_extra != 0.0) {
    const double r = velocity / p_.stribeck_velocity;
    level += p_.stribeck_extra * std::exp(-r * r);
  }
  return level * smooth_sign(velocity / p_.friction_smoothing_velocity);
}

double LinearMotorAxis::cogging_force(double position) const {
  // Paper 000, eq. 4-2.
  double f = 0.0;
  for (std::size_t i = 0; i < wavenumbers_.size(); ++i) {
    const double phase = wavenumbers_[i] * position;
    f += p_.cogging[i].sine * std::sin(phase) + p_.cogging[i].cosine * std::cos(phase);
  }
  return f;
}

void LinearMotorAxis::advance_piece(double t0, double duration, double input, double step_level) {
  const Disturbance& d = p_.disturbance;
  if (linear_ && smooth_part_is_constant(d)) {
    exact_.step(state(), duration, input + smooth_part(d, t0) + step_level);
    return;
  }
  const double inv_mass = 1.0 / p_.mass;
  const double damping = p_.damping;
  const long long n = substep_count(kLinearMotorAxisOwner, duration, p_.max_substep_s);
  double y = state()(0);
  double v = state()(1);
  // Paper 000, eq. 2-43 / A.1: M y'' = u - B y' - Ff(y') - Fr(y) + d.
  rk4_second_order(y, v, t0, duration, n, [&](double t, double yy, double vv) {
    const double force = input + smooth_part(d, t) + step_level - damping * vv -
                         friction_force(vv) - cogging_force(yy);
    return force * inv_mass;
  });
  state() << y, v;
}

std::unique_ptr<AxisPlant> LinearMotorAxis::clone() const {
  return std::make_unique<LinearMotorAxis>(*this);
}

std::string LinearMotorAxis::describe() const {
  std::ostringstream out;
  out << "LinearMotorAxis (paper 000 eq. 2-43/A.3/4-2): M=" << p_.mass
      << " V/(m/s^2), B=" << p_.damping << " V/(m/s), A=" << p_.coulomb << " V";
  if (p_.stribeck_extra != 0.0) {
    out << " (+Stribeck " << p_.stribeck_extra << " V at " << p_.stribeck_velocity << " m/s)";
  }
  out << ", smoothing " << p_.friction_smoothing_velocity
      << " m/s, cogging P=" << p_.cogging_pitch_m << " m";
  if (p_.cogging.empty()) {
    out << " none";
  } else {
    out << " {";
    for (std::size_t i = 0; i < p_.cogging.size(); ++i) {
      out << (i ? ", " : "") << p_.cogging[i].order << ":(" << p_.cogging[i].sine << ", "
          << p_.cogging[i].cosine << ")";
    }
    out << "} V";
  }
  out << ", d=" << describe_disturbance(p_.disturbance, "V") << ", max_substep=" << p_.max_substep_s
      << " s";
  return out.str();
}

}  // namespace netmc::plant
