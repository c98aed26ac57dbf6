#include "control/data_driven/compact_form_mfac.hpp"

#include <cmath>
#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {

CompactFormMfacAxis::CompactFormMfacAxis(const CompactFormMfacGains& gains)
    : gains_(gains), full_(full_form_gains(gains)) {
  require_positive(gains_.mu, "mfac mu");
  require_positive(gains_.lambda, "mfac lambda");
  require_positive(gains_.rho, "mfac rho");
  require_positive(gains_.eta, "mfac eta");
  require_non_negative(gains_.epsilon, "mfac epsilon");
  require_positive(gains_.phi_initial, "mfac phi_initial");
  require_non_negative(gains_.contour_weight, "mfac delta");
  reset(0.0);
}

void CompactFormMfacAxis::reset(double position) {
  phi_ = gains_.phi_initial;
  full_.reset();
  previous_position_ = position;
  previous_command_ = 0.0;
  previous_increment_ = 0.0;
}

AxisPrediction CompactFormMfacAxis::predict(double position, double desired, double desired_next,
                                            double desired_after, double contour_error) {
  const double dy = position - previous_position_;
  AxisPrediction p;
  p.rule = IncrementRule::least_squares;
  p.tracking_error = position - desired;
  p.contour_error = contour_error;
  p.contour_weight = gains_.contour_weight;
  p.rho = gains_.rho;
  p.lambda = gains_.lambda;
  if (gains_.data_model == DataModelForm::full) {
    full_.update(dy);
    double next = 0.0, after = 0.0;
    full_.free_response(position, 0.0, next, after);
    p.free_error = after - desired_after;
    p.gain = full_.b0();
  } else {
    const double du = previous_increment_;
    phi_ += gains_.eta * du * (dy - phi_ * du) / (gains_.mu + du * du);
    if (std::abs(phi_) <= gains_.epsilon || std::abs(du) <= gains_.epsilon || phi_ * gains_.phi_initial < 0.0) {
      phi_ = gains_.phi_initial;
    }
    p.free_error = position - desired_next;
    p.gain = phi_;
  }
  previous_position_ = position;
  return p;
}

double CompactFormMfacAxis::commit(double increment) {
  if (gains_.data_model == DataModelForm::full) full_.commit(increment);
  previous_command_ += increment;
  previous_increment_ = increment;
  return previous_command_;
}

std::unique_ptr<DataDrivenAxisLaw> CompactFormMfacAxis::clone() const {
  return std::make_unique<CompactFormMfacAxis>(*this);
}

std::string CompactFormMfacAxis::describe() const {
  std::ostringstream out;
  out << (gains_.data_model == DataModelForm::full ? "MFAC" : "CFDL-MFAC") << "(mu=" << gains_.mu
      << ", lambda=" << gains_.lambda << ", rho=" << gains_.rho << ", eta=" << gains_.eta
      << ", Phi(1)=" << gains_.phi_initial << ", delta=" << gains_.contour_weight
      << ", data_model=" << data_model_form_name(gains_.data_model) << ")";
  return out.str();
}

NamedEstimate CompactFormMfacAxis::estimate(std::size_t index) const {
  if (gains_.data_model == DataModelForm::full) {
    switch (index) {
      case 0: return {"phi_hat", "um/V", full_.b0()};
      case 1: return {"a1_hat", "1", full_.a1()};
      default: return {"a2_hat", "1", full_.a2()};
    }
  }
  return {"phi_hat", "um/V", phi_};
}

}  // namespace netmc::control
