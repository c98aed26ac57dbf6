#include "plant/flexible_linear_motor_axis.hpp"

#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "plant/parameter_checks.hpp"

namespace netmc::plant {
namespace {

constexpr const char* kFlexibleLinearMotorAxisOwner = "FlexibleLinearMotorAxis";

FlexibleLinearMotorParameters validated(FlexibleLinearMotorParameters p) {
  require_finite(kFlexibleLinearMotorAxisOwner, "load_fraction", p.load_fraction);
  if (!(p.load_fraction > 0.0 && p.load_fraction < 1.0)) {
    throw std::invalid_argument(std::string(kFlexibleLinearMotorAxisOwner) + ": load_fraction must be in (0, 1) (got " +
                                std::to_string(p.load_fraction) + ")");
  }
  require_positive(kFlexibleLinearMotorAxisOwner, "mode_frequency_hz", p.mode_frequency_hz);
  require_non_negative(kFlexibleLinearMotorAxisOwner, "mode_damping_ratio", p.mode_damping_ratio);
  require_positive(kFlexibleLinearMotorAxisOwner, "current_loop_hz", p.current_loop_hz);
  validate_disturbance(p.disturbance, kFlexibleLinearMotorAxisOwner);
  require_positive(kFlexibleLinearMotorAxisOwner, "max_substep_s", p.max_substep_s);
  // The rigid part (mass, friction, cogging) is checked by LinearMotorAxis, which names itself.
  p.motor.disturbance = Disturbance{};
  return p;
}

}  // namespace

FlexibleLinearMotorAxis::FlexibleLinearMotorAxis(FlexibleLinearMotorParameters p)
    : PiecewiseAxisPlant(kFlexibleLinearMotorAxisOwner), p_(validated(std::move(p))), rigid_(p_.motor) {
  const double total = p_.motor.mass;
  load_mass_ = p_.load_fraction * total;
  motor_mass_ = total - load_mass_;
  // The relative coordinate q = x_m - x_l has the reduced mass M_m M_l / M: choose k and c so
  // that q'' + 2 zeta w q' + w^2 q = force / M_m (appendix A's mode).
  const double w = 2.0 * std::numbers::pi * p_.mode_frequency_hz;
  const double reduced = motor_mass_ * load_mass_ / total;
  stiffness_ = w * w * reduced;
  coupling_damping_ = 2.0 * p_.mode_damping_ratio * w * reduced;
  current_loop_rate_ = 2.0 * std::numbers::pi * p_.current_loop_hz;
}

void FlexibleLinearMotorAxis::reset_state(double position, double velocity) {
  // Both masses move together, the spring is relaxed and the drive gives no force.
  z_ = {position, velocity, position, velocity, 0.0};
}

FlexibleLinearMotorAxis::State FlexibleLinearMotorAxis::derivative(const State& z, double command) const {
  const double coupling = stiffness_ * (z[kMotorPosition] - z[kLoadPosition]) +
                          coupling_damping_ * (z[kMotorVelocity] - z[kLoadVelocity]);
  // Thesis A.1-A.3 and 4-2 on the motor side.
  const double motor_force = z[kDriveForce] - p_.motor.damping * z[kMotorVelocity] -
                             rigid_.friction_force(z[kMotorVelocity]) -
                             rigid_.cogging_force(z[kMotorPosition]) - coupling;
  State d;
  d[kMotorPosition] = z[kMotorVelocity];
  d[kMotorVelocity] = motor_force / motor_mass_;
  d[kLoadPosition] = z[kLoadVelocity];
  d[kLoadVelocity] = coupling / load_mass_;
  // Appendix A: the current loop as a first-order lag of its bandwidth.
  d[kDriveForce] = current_loop_rate_ * (command - z[kDriveForce]);
  return d;
}

void FlexibleLinearMotorAxis::advance_piece(double t0, double duration, double input, double step_level) {
  const Disturbance& dist = p_.disturbance;
  const long long n = substep_count(kFlexibleLinearMotorAxisOwner, duration, p_.max_substep_s);
  const double h = duration / static_cast<double>(n);
  const double half = 0.5 * h;
  auto shifted = [](const State& z, const State& dz, double scale) {
    State out;
    for (int i = 0; i < kSize; ++i) out[i] = z[i] + scale * dz[i];
    return out;
  };
  for (long long i = 0; i < n; ++i) {
    // Sub-step start from the index so t does not drift (as rk4_second_order).
    const double t = t0 + static_cast<double>(i) * h;
    const double u0 = input + smooth_part(dist, t) + step_level;
    const double u_half = input + smooth_part(dist, t + half) + step_level;
    const double u1 = input + smooth_part(dist, t + h) + step_level;
    const State k1 = derivative(z_, u0);
    const State k2 = derivative(shifted(z_, k1, half), u_half);
    const State k3 = derivative(shifted(z_, k2, half), u_half);
    const State k4 = derivative(shifted(z_, k3, h), u1);
    for (int j = 0; j < kSize; ++j) z_[j] += (h / 6.0) * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
  }
}

std::unique_ptr<AxisPlant> FlexibleLinearMotorAxis::clone() const {
  return std::make_unique<FlexibleLinearMotorAxis>(*this);
}

std::string FlexibleLinearMotorAxis::describe() const {
  const LinearMotorParameters& m = p_.motor;
  std::ostringstream out;
  out << "FlexibleLinearMotorAxis (paper 000 A.1-A.3/4-2, two masses, current loop): M=" << m.mass
      << " V/(m/s^2) (carriage share " << p_.load_fraction << "), B=" << m.damping
      << " V/(m/s), A=" << m.coulomb << " V (+Stribeck " << m.stribeck_extra << " V at "
      << m.stribeck_velocity << " m/s), mode " << p_.mode_frequency_hz << " Hz zeta "
      << p_.mode_damping_ratio << ", current loop " << p_.current_loop_hz << " Hz, cogging P="
      << m.cogging_pitch_m << " m";
  if (m.cogging.empty()) {
    out << " none";
  } else {
    out << " {";
    for (std::size_t i = 0; i < m.cogging.size(); ++i) {
      out << (i ? ", " : "") << m.cogging[i].order << ":(" << m.cogging[i].sine << ", "
          << m.cogging[i].cosine << ")";
    }
    out << "} V";
  }
  out << ", d=" << describe_disturbance(p_.disturbance, "V") << ", max_substep=" << p_.max_substep_s
      << " s";
  return out.str();
}

}  // namespace netmc::plant
