#include "control/data_driven/mfa_dtsmc_axis.hpp"

#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {
MfaDtsmcAxis::MfaDtsmcAxis(const MfaDtsmcGains& gains, double sample_period_s)
    : gains_(gains),
      estimator_(gains.estimator),
      full_(full_form_gains(gains.estimator)),
      sliding_(gains.sliding, sample_period_s) {
  require_non_negative(gains_.switching_gain, "mfa-dtsmc lambda_s");
  require_non_negative(gains_.contour_weight, "mfa-dtsmc delta");
}

void MfaDtsmcAxis::reset(double position) {
  estimator_.reset();
  full_.reset();
  previous_position_ = position;
  previous_error_ = 0.0;
  previous_command_ = 0.0;
  previous_increment_ = 0.0;
  s_ = 0.0;
}

AxisPrediction MfaDtsmcAxis::predict(double position, double desired, double desired_next, double desired_after,
                                     double contour_error) {
  const auto& g = gains_.sliding;
  const double delta_eps = gains_.contour_weight * contour_error;
  AxisPrediction p;
  p.rule = IncrementRule::reaching_target;
  p.tracking_error = position - desired;
  p.contour_error = contour_error;
  p.contour_weight = gains_.contour_weight;
  double e = 0.0, previous_e = 0.0;
  if (gains_.data_model == DataModelForm::full) {
    // Psi^ dd^ of k-1 in the residual, as kappa in eq. 14; of k in the prediction.
    const double disturbance = estimator_.psi() * estimator_.disturbance_increment();
    estimator_.update_disturbance(full_.update(position - previous_position_, disturbance));
    double next = 0.0, after = 0.0;
    full_.free_response(position, estimator_.psi() * estimator_.disturbance_increment(), next, after);
    previous_e = position - desired + delta_eps;  // e(k), measured (eq. 16)
    e = next - desired_next + delta_eps;          // e(k+1), predicted with du(k) = 0
    p.free_error = after - desired_after;
    p.gain = full_.b0();
  } else {
    estimator_.update(position - previous_position_, previous_increment_);
    previous_e = previous_error_;
    e = position - desired + delta_eps;  // eq. 16
    p.free_error = position + estimator_.psi() * estimator_.disturbance_increment() - desired_next;
    p.gain = estimator_.phi();
  }
  s_ = sliding_.sliding_variable(e, previous_e);  // eq. 17
  // eq. 24 with H = lambda(k) = 0, plus eq. 25's switching step, as the composite error wanted
  // one sample after e (the composition adds delta eps and divides by the gain).
  p.target = sliding_.next_sliding_variable(s_) / g.lambda1 + (1.0 - g.beta) * e -
             g.lambda2 / g.lambda1 * signed_power(e, g.alpha) - gains_.switching_gain * signum(s_);
  previous_position_ = position;
  previous_error_ = e;
  return p;
}

double MfaDtsmcAxis::commit(double increment) {
  if (gains_.data_model == DataModelForm::full) full_.commit(increment);
  previous_command_ += increment;
  previous_increment_ = increment;
  return previous_command_;
}

std::unique_ptr<DataDrivenAxisLaw> MfaDtsmcAxis::clone() const { return std::make_unique<MfaDtsmcAxis>(*this); }

std::string MfaDtsmcAxis::describe() const {
  std::ostringstream out;
  out << "MFA-DTSMC(" << sliding_.describe() << ", lambda_s=" << gains_.switching_gain
      << ", delta=" << gains_.contour_weight << ", data_model=" << data_model_form_name(gains_.data_model) << "; "
      << estimator_.describe();
  if (gains_.data_model == DataModelForm::full) out << "; " << full_.describe();
  out << ")";
  return out.str();
}

NamedEstimate MfaDtsmcAxis::estimate(std::size_t index) const {
  const bool full = gains_.data_model == DataModelForm::full;
  switch (index) {
    case 0: return {"phi_hat", "um/V", full ? full_.b0() : estimator_.phi()};
    case 1: return {"psi_hat", "um/V", estimator_.psi()};
    case 2: return {"disturbance_increment_hat", "V", estimator_.disturbance_increment()};
    case 3: return {"disturbance_hat", "V", estimator_.disturbance()};
    case 4: return {"sliding_variable", "um", s_};
    case 5: return {"a1_hat", "1", full_.a1()};
    default: return {"a2_hat", "1", full_.a2()};
  }
}

}  // namespace netmc::control
