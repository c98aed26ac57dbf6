#pragma once
// Third-order linear extended state observer (LESO) of ADRC: estimates position z1, velocity z2
// and the "total disturbance" z3 (everything but b0*u in the acceleration) of one axis.

#include <Eigen/Dense>

namespace netmc::control {

enum class Discretization {
  // paper 001, eq. 9, as printed: continuous observer stepped by forward Euler, poles at 1 - w0 h.
  forward_euler,
  // Exact (zero-order-hold) discretization of the extended plant model (a chain of three
  // integrators with input gain b0), observer gains placing all poles at exp(-w0 h)
  // (Miklosovic, Radke and Gao, 2006). Exact for inputs held over the period.
  zero_order_hold,
};

class ExtendedStateObserver {
 public:
  // bandwidth w0 [rad/s]: all three observer poles at -w0 (s-plane) or their discrete image;
  // input_gain b0; sample period h [s].
  ExtendedStateObserver(double bandwidth, double input_gain, double sample_period_s,
                        Discretization discretization = Discretization::forward_euler);

  void reset(double position, double velocity = 0.0, double disturbance = 0.0);
  // One step with the measured position y(k) and the input u(k) that acts during the period.
  void update(double measured_position, double input);

  double position() const { return z_(0); }
  double velocity() const { return z_(1); }
  double disturbance() const { return z_(2); }
  double input_gain() const { return b0_; }

 private:
  double b0_;
  Eigen::Vector3d z_ = Eigen::Vector3d::Zero();
  // z(k+1) = transition * z(k) + input_column * u(k) + measurement_column * y(k)
  Eigen::Matrix3d transition_;
  Eigen::Vector3d input_column_;
  Eigen::Vector3d measurement_column_;
};

}  // namespace netmc::control
