#include "control/axis/extended_state_observer.hpp"

#include <cmath>

#include "control/parameter_check.hpp"

namespace netmc::control {

ExtendedStateObserver::ExtendedStateObserver(double bandwidth, double input_gain,
                                             double sample_period_s, Discretization discretization)
    : b0_(require_positive(input_gain, "observer b0")) {
  const double w0 = require_positive(bandwidth, "observer bandwidth w0");
  const double h = require_positive(sample_period_s, "sample period");

  if (discretization == Discretization::forward_euler) {
    // Continuous observer z' = (A - L C) z + B u + L y with L = [3w0, 3w0^2, w0^3] (all poles at
    // -w0), stepped by forward Euler (paper 001, eq. 9).
    Eigen::Matrix3d observer_matrix;
    observer_matrix << -3.0 * w0, 1.0, 0.0,
                       -3.0 * w0 * w0, 0.0, 1.0,
                       -w0 * w0 * w0, 0.0, 0.0;
    transition_ = Eigen::Matrix3d::Identity() + h * observer_matrix;
    input_column_ = Eigen::Vector3d(0.0, h * b0_, 0.0);
    measurement_column_ = h * Eigen::Vector3d(3.0 * w0, 3.0 * w0 * w0, w0 * w0 * w0);
  } else {
    // Exact model: z(k+1) = Phi z(k) + Gamma u(k) + L (y(k) - z1(k)) with Phi = exp(A h) of the
    // integrator chain. det(lambda I - (Phi - L C)) = mu^3 + l1 mu^2 + (h l2 + h^2 l3 / 2) mu
    // + h^2 l3 with mu = lambda - 1; matching (lambda - beta)^3, beta = exp(-w0 h), c = 1 - beta:
    const double c = 1.0 - std::exp(-w0 * h);
    const double l1 = 3.0 * c;
    const double l3 = c * c * c / (h * h);
    const double l2 = (3.0 * c * c - 0.5 * c * c * c) / h;
    Eigen::Matrix3d exact_model;
    exact_model << 1.0, h, 0.5 * h * h,
                   0.0, 1.0, h,
                   0.0, 0.0, 1.0;
    measurement_column_ = Eigen::Vector3d(l1, l2, l3);
    transition_ = exact_model;
    transition_.col(0) -= measurement_column_;
    input_column_ = Eigen::Vector3d(0.5 * b0_ * h * h, b0_ * h, 0.0);
  }
}

void ExtendedStateObserver::reset(double position, double velocity, double disturbance) {
  z_ = Eigen::Vector3d(position, velocity, disturbance);
}

void ExtendedStateObserver::update(double measured_position, double input) {
  z_ = transition_ * z_ + input_column_ * input + measurement_column_ * measured_position;
}

}  // namespace netmc::control
