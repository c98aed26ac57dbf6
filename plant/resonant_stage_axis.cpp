#include "plant/resonant_stage_axis.hpp"

#include <numbers>
#include <sstream>
#include <string>
#include <utility>

#include "plant/parameter_checks.hpp"
#include "plant/rk4_integrator.hpp"

namespace netmc::plant {
namespace {

constexpr const char* kResonantStageAxisOwner = "ResonantStageAxis";

ResonantStageParameters validated(ResonantStageParameters p) {
  require_positive(kResonantStageAxisOwner, "mass", p.mass);
  for (std::size_t i = 0; i < p.modes.size(); ++i) {
    const std::string name = "modes[" + std::to_string(i) + "]";
    require_finite(kResonantStageAxisOwner, name + ".gain", p.modes[i].gain);
    require_non_negative(kResonantStageAxisOwner, name + ".damping_ratio", p.modes[i].damping_ratio);
    require_positive(kResonantStageAxisOwner, name + ".frequency_hz", p.modes[i].frequency_hz);
  }
  validate_disturbance(p.disturbance, kResonantStageAxisOwner);
  require_positive(kResonantStageAxisOwner, "max_substep_s", p.max_substep_s);
  return p;
}

}  // namespace

ResonantStageAxis::ResonantStageAxis(ResonantStageParameters p)
    : PiecewiseAxisPlant(kResonantStageAxisOwner), p_(validated(std::move(p))) {
  modes_.reserve(p_.modes.size());
  for (const ResonanceMode& m : p_.modes) {
    // Paper 004, eq. 1: denominator s^2 + 4 pi x f s + (2 pi f)^2 = s^2 + 2 x w s + w^2.
    const double w = 2.0 * std::numbers::pi * m.frequency_hz;
    ModeState s;
    s.gain = m.gain;
    s.stiffness = w * w;
    s.damping = 2.0 * m.damping_ratio * w;
    Eigen::Matrix2d a;
    a << 0.0, 1.0, -s.stiffness, -s.damping;
    s.exact = ExactDiscretizer(a, Eigen::Vector2d(0.0, m.gain));
    modes_.push_back(s);
  }
}

double ResonantStageAxis::position() const {
  double y = rigid_(0);
  for (const ModeState& m : modes_) y += m.z(0);
  return y;
}

double ResonantStageAxis::velocity() const {
  double v = rigid_(1);
  for (const ModeState& m : modes_) v += m.z(1);
  return v;
}

void ResonantStageAxis::reset_state(double position, double velocity) {
  // The modes start at rest; the whole given motion belongs to the rigid body.
  rigid_ << position, velocity;
  for (ModeState& m : modes_) m.z.setZero();
}

void ResonantStageAxis::advance_piece(double t0, double duration, double input, double step_level) {
  const Disturbance& d = p_.disturbance;
  const double inv_mass = 1.0 / p_.mass;
  if (smooth_part_is_constant(d)) {
    const double force = input + smooth_part(d, t0) + step_level;
    // Rigid body 1/(m s^2) under a constant force: the closed form is exact.
    const double acc = force * inv_mass;
    rigid_(0) += duration * (rigid_(1) + 0.5 * acc * duration);
    rigid_(1) += acc * duration;
    for (ModeState& m : modes_) m.exact.step(m.z, duration, force);
    return;
  }
  // RK4 on the full block-diagonal system equals RK4 on each block with the same sub-steps.
  const long long n = substep_count(kResonantStageAxisOwner, duration, p_.max_substep_s);
  auto force = [&](double t) { return input + smooth_part(d, t) + step_level; };
  double x = rigid_(0);
  double v = rigid_(1);
  rk4_second_order(x, v, t0, duration, n,
                   [&](double t, double, double) { return force(t) * inv_mass; });
  rigid_ << x, v;
  for (ModeState& m : modes_) {
    double q = m.z(0);
    double qd = m.z(1);
    const double k = m.gain;
    const double c = m.damping;
    const double s = m.stiffness;
    rk4_second_order(q, qd, t0, duration, n, [&](double t, double qq, double vv) {
      return k * force(t) - c * vv - s * qq;
    });
    m.z << q, qd;
  }
}

std::unique_ptr<AxisPlant> ResonantStageAxis::clone() const {
  return std::make_unique<ResonantStageAxis>(*this);
}

std::string ResonantStageAxis::describe() const {
  std::ostringstream out;
  out << "ResonantStageAxis (paper 004 eq. 1): m=" << p_.mass << " kg, modes";
  if (p_.modes.empty()) out << " none";
  for (std::size_t i = 0; i < p_.modes.size(); ++i) {
    out << (i ? "; " : " ") << "K=" << p_.modes[i].gain << " x=" << p_.modes[i].damping_ratio
        << " f=" << p_.modes[i].frequency_hz << " Hz";
  }
  out << ", d=" << describe_disturbance(p_.disturbance, "N") << ", max_substep=" << p_.max_substep_s
      << " s";
  return out.str();
}

}  // namespace netmc::plant
