#include "control/data_driven/data_model_estimator.hpp"

#include <cmath>
#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

// Theorem 2 (digest 3.5) asks for steps in (0.5, 1); the compact-form MFAC of C3 uses eta = 1,
// so (0, 1] is accepted and the stricter range is left to the caller.
double require_step(double value, std::string_view field) {
  if (!std::isfinite(value) || value <= 0.0 || value > 1.0) {
    throw std::invalid_argument(std::string(field) + ": expected a step in (0, 1], got " + std::to_string(value));
  }
  return value;
}

}  // namespace

DataModelEstimator::DataModelEstimator(const DataModelEstimatorGains& gains) : gains_(gains) {
  require_step(gains_.eta, "data model eta");
  require_step(gains_.tau, "data model tau");
  require_step(gains_.sigma, "data model sigma");
  require_positive(gains_.mu, "data model mu");
  require_positive(gains_.gamma, "data model gamma");
  require_positive(gains_.rho, "data model rho");
  require_non_negative(gains_.epsilon, "data model epsilon");
  require_positive(gains_.phi_initial, "data model phi_initial");
  require_positive(gains_.psi_initial, "data model psi_initial");
  require_positive(gains_.disturbance_bound, "data model disturbance_bound");
  reset();
}

void DataModelEstimator::reset() {
  phi_ = gains_.phi_initial;
  psi_ = gains_.psi_initial;
  increment_ = 0.0;
  disturbance_ = 0.0;
}

void DataModelEstimator::update(double output_increment, double previous_input_increment) {
  const double du = previous_input_increment;
  const double dd = increment_;
  const double residual = output_increment - (psi_ * dd + phi_ * du);  // dy(k) - kappa(k-1)
  // All three from the estimates of k-1 (eq. 14a-c).
  double phi = phi_ + gains_.eta * du * residual / (gains_.mu + du * du);
  double psi = psi_ + gains_.tau * dd * residual / (gains_.gamma + dd * dd);
  double increment = dd + gains_.sigma * psi_ * residual / (gains_.rho + psi_ * psi_);
  // Resets (sec. 3.2).
  if (std::abs(phi) <= gains_.epsilon || std::abs(du) <= gains_.epsilon) phi = gains_.phi_initial;
  if (std::abs(psi) <= gains_.epsilon || std::abs(dd) <= gains_.epsilon) psi = gains_.psi_initial;
  if (std::abs(increment) >= 2.0 * gains_.disturbance_bound) {
    increment = 0.0;
    disturbance_ = 0.0;
  }
  phi_ = phi;
  psi_ = psi;
  increment_ = increment;
  disturbance_ += increment;
}

std::string DataModelEstimator::describe() const {
  std::ostringstream out;
  out << "eta=" << gains_.eta << ", mu=" << gains_.mu << ", tau=" << gains_.tau << ", gamma=" << gains_.gamma
      << ", sigma=" << gains_.sigma << ", rho=" << gains_.rho << ", Phi(1)=" << gains_.phi_initial
      << ", Psi(1)=" << gains_.psi_initial << ", d0=" << gains_.disturbance_bound;
  return out.str();
}

}  // namespace netmc::control
