#include "control/data_driven/data_model_estimator.hpp"

#include <cmath>
#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

// Theorem 2 (paper 002, section 5) asks for steps in (0.5, 1); the compact-form MFAC of C3 uses eta = 1,
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
  const double residual = output_increment - (psi_ * increment_ + phi_ * du);  // dy(k) - kappa(k-1)
  // All three from the estimates of k-1 (eq. 14a-c).
  double phi = phi_ + gains_.eta * du * residual / (gains_.mu + du * du);
  // Resets (paper 002, section 3.3).
  if (std::abs(phi) <= gains_.epsilon || std::abs(du) <= gains_.epsilon) phi = gains_.phi_initial;
  phi_ = phi;
  update_disturbance(residual);
}

void DataModelEstimator::update_disturbance(double residual) {
  const double dd = increment_;
  double psi = psi_ + gains_.tau * dd * residual / (gains_.gamma + dd * dd);
  double increment = dd + gains_.sigma * psi_ * residual / (gains_.rho + psi_ * psi_);
  if (std::abs(psi) <= gains_.epsilon || std::abs(dd) <= gains_.epsilon) psi = gains_.psi_initial;
  if (std::abs(increment) >= 2.0 * gains_.disturbance_bound) {
    increment = 0.0;
    disturbance_ = 0.0;
  }
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

const char* data_model_form_name(DataModelForm form) {
  return form == DataModelForm::full ? "full" : "compact";
}

DataModelForm parse_data_model_form(std::string_view name, std::string_view field) {
  if (name == "compact") return DataModelForm::compact;
  if (name == "full") return DataModelForm::full;
  std::string message(field);
  message.append(": expected 'compact' (paper 002, eq. 9) or 'full' (L_y = 2, d = 1), got '");
  message.append(name.substr(0, 64));
  message.append("'");
  throw std::invalid_argument(message);
}

FullFormDataModel::FullFormDataModel(const FullFormDataModelGains& gains) : gains_(gains) {
  require_step(gains_.eta, "full-form data model eta");
  require_positive(gains_.mu, "full-form data model mu");
  require_non_negative(gains_.epsilon, "full-form data model epsilon");
  require_positive(gains_.b0_initial, "full-form data model b0_initial");
  require_finite(gains_.a1_initial, "full-form data model a1_initial");
  require_finite(gains_.a2_initial, "full-form data model a2_initial");
  reset();
}

void FullFormDataModel::reset() {
  a1_ = gains_.a1_initial;
  a2_ = gains_.a2_initial;
  b0_ = gains_.b0_initial;
  dy0_ = dy1_ = dy2_ = du1_ = du2_ = 0.0;
}

double FullFormDataModel::update(double output_increment, double disturbance_part) {
  // Regressor of dy(k): dy(k-1), dy(k-2), du(k-2).
  const double residual = output_increment - (a1_ * dy1_ + a2_ * dy2_ + b0_ * du2_) - disturbance_part;
  const double step = gains_.eta * residual / (gains_.mu + dy1_ * dy1_ + dy2_ * dy2_ + du2_ * du2_);
  a1_ += step * dy1_;
  a2_ += step * dy2_;
  b0_ += step * du2_;
  if (std::abs(b0_) <= gains_.epsilon || std::abs(du2_) <= gains_.epsilon || b0_ * gains_.b0_initial < 0.0) {
    b0_ = gains_.b0_initial;
  }
  dy0_ = output_increment;
  return residual;
}

void FullFormDataModel::free_response(double position, double disturbance_part, double& next, double& after) const {
  const double first = a1_ * dy0_ + a2_ * dy1_ + b0_ * du1_ + disturbance_part;  // dy(k+1)
  const double second = a1_ * first + a2_ * dy0_ + disturbance_part;             // dy(k+2), du(k) = 0
  next = position + first;
  after = next + second;
}

void FullFormDataModel::commit(double input_increment) {
  dy2_ = dy1_;
  dy1_ = dy0_;
  du2_ = du1_;
  du1_ = input_increment;
}

std::string FullFormDataModel::describe() const {
  std::ostringstream out;
  out << "full-form L_y=2 d=1: eta=" << gains_.eta << ", mu=" << gains_.mu << ", b0(1)=" << gains_.b0_initial
      << ", a(1)=(" << gains_.a1_initial << ", " << gains_.a2_initial << ")";
  return out.str();
}

}  // namespace netmc::control
