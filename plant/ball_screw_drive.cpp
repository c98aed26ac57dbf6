#include "plant/ball_screw_drive.hpp"

#include <sstream>

#include "plant/parameter_checks.hpp"
#include "plant/rk4_integrator.hpp"

namespace netmc::plant {
namespace {

constexpr const char* kBallScrewDriveOwner = "BallScrewDrive";

BallScrewParameters validated(BallScrewParameters p) {
  require_positive(kBallScrewDriveOwner, "inertia", p.inertia);
  require_non_negative(kBallScrewDriveOwner, "damping", p.damping);
  require_positive(kBallScrewDriveOwner, "amplifier_gain", p.amplifier_gain);
  require_positive(kBallScrewDriveOwner, "torque_constant", p.torque_constant);
  require_positive(kBallScrewDriveOwner, "lead_m_per_rad", p.lead_m_per_rad);
  validate_disturbance(p.disturbance, kBallScrewDriveOwner);
  require_positive(kBallScrewDriveOwner, "max_substep_s", p.max_substep_s);
  return p;
}

}  // namespace

BallScrewDrive::BallScrewDrive(BallScrewParameters p)
    : TwoStateAxisPlant(kBallScrewDriveOwner),
      p_(validated(p)),
      // Paper 002, eq. 1 divided by J s: motor torque Ka Kt (u + d) drives J theta'' + B theta',
      // and y = rg theta.
      gain_(p_.amplifier_gain * p_.torque_constant * p_.lead_m_per_rad / p_.inertia),
      rate_(p_.damping / p_.inertia) {
  Eigen::Matrix2d a;
  a << 0.0, 1.0, 0.0, -rate_;
  exact_ = ExactDiscretizer(a, Eigen::Vector2d(0.0, gain_));
}

void BallScrewDrive::advance_piece(double t0, double duration, double input, double step_level) {
  const Disturbance& d = p_.disturbance;
  if (smooth_part_is_constant(d)) {
    exact_.step(state(), duration, input + smooth_part(d, t0) + step_level);
    return;
  }
  const double k = gain_;
  const double r = rate_;
  const long long n = substep_count(kBallScrewDriveOwner, duration, p_.max_substep_s);
  double y = state()(0);
  double v = state()(1);
  // Paper 002, eq. 1: y'' = -(B/J) y' + (Ka Kt rg / J) (u + d(t)).
  rk4_second_order(y, v, t0, duration, n, [&](double t, double, double vv) {
    return -r * vv + k * (input + smooth_part(d, t) + step_level);
  });
  state() << y, v;
}

std::unique_ptr<AxisPlant> BallScrewDrive::clone() const {
  return std::make_unique<BallScrewDrive>(*this);
}

std::string BallScrewDrive::describe() const {
  std::ostringstream out;
  out << "BallScrewDrive (paper 002 eq. 1): J=" << p_.inertia << " kg m^2, B=" << p_.damping
      << " N m s/rad, Ka=" << p_.amplifier_gain << " A/V, Kt=" << p_.torque_constant
      << " N m/A, rg=" << p_.lead_m_per_rad << " m/rad";
  if (rate_ > 0.0) out << " (steady " << gain_ / rate_ << " m/s per V)";
  out << ", d=" << describe_disturbance(p_.disturbance, "V") << ", max_substep=" << p_.max_substep_s
      << " s";
  return out.str();
}

}  // namespace netmc::plant
