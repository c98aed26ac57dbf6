#include "control/extended_state_observer.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include "control/parameter_check.hpp"

namespace netmc::control {

ExtendedStateObserver::ExtendedStateObserver(double bandwidth, double input_gain,
                                             double sample_period_s, Discretization discretization)
    : b0_(require_positive(input_gain, "observer b0")) {
  const double w0 = require_positive(bandwidth, "observer bandwidth w0");
  const double h = require_positive(sample_period_s, "sample period");

  // Continuous observer: z' = (A - L C) z + B u + L y, with observer gains L = [3w0, 3w0^2, w0^3]
  // placing all poles at -w0 (paper 001, eq. 9 before discretization).
  Eigen::Matrix3d observer_matrix;
  observer_matrix << -3.0 * w0, 1.0, 0.0,
                     -3.0 * w0 * w0, 0.0, 1.0,
                     -w0 * w0 * w0, 0.0, 0.0;
  const Eigen::Vector3d input_direction(0.0, b0_, 0.0);
  const Eigen::Vector3d gain(3.0 * w0, 3.0 * w0 * w0, w0 * w0 * w0);

  if (discretization == Discretization::forward_euler) {
    transition_ = Eigen::Matrix3d::Identity() + h * observer_matrix;
    input_column_ = h * input_direction;
    measurement_column_ = h * gain;
  } else {
    // Van Loan's augmented exponential gives exp(F h) and the integral of exp(F s) G at once.
    Eigen::Matrix<double, 5, 5> augmented = Eigen::Matrix<double, 5, 5>::Zero();
    augmented.topLeftCorner<3, 3>() = observer_matrix * h;
    augmented.block<3, 1>(0, 3) = input_direction * h;
    augmented.block<3, 1>(0, 4) = gain * h;
    const Eigen::Matrix<double, 5, 5> exponential = augmented.exp();
    transition_ = exponential.topLeftCorner<3, 3>();
    input_column_ = exponential.block<3, 1>(0, 3);
    measurement_column_ = exponential.block<3, 1>(0, 4);
  }
}

void ExtendedStateObserver::reset(double position, double velocity, double disturbance) {
  z_ = Eigen::Vector3d(position, velocity, disturbance);
}

void ExtendedStateObserver::update(double measured_position, double input) {
  z_ = transition_ * z_ + input_column_ * input + measurement_column_ * measured_position;
}

}  // namespace netmc::control
