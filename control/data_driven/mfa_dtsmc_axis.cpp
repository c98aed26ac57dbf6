#include "control/data_driven/mfa_dtsmc_axis.hpp"

#include <sstream>

#include "control/parameter_check.hpp"

namespace netmc::control {
namespace {

double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

}  // namespace

MfaDtsmcAxis::MfaDtsmcAxis(const MfaDtsmcGains& gains, double sample_period_s)
    : gains_(gains), estimator_(gains.estimator), sliding_(gains.sliding, sample_period_s) {
  require_non_negative(gains_.switching_gain, "mfa-dtsmc lambda_s");
  require_non_negative(gains_.contour_weight, "mfa-dtsmc delta");
}

void MfaDtsmcAxis::reset(double position) {
  estimator_.reset();
  previous_position_ = position;
  previous_error_ = 0.0;
  previous_command_ = 0.0;
  previous_increment_ = 0.0;
  s_ = 0.0;
}

double MfaDtsmcAxis::command(double position, double desired, double desired_next, double contour_error) {
  estimator_.update(position - previous_position_, previous_increment_);
  const auto& g = gains_.sliding;
  const double delta_eps = gains_.contour_weight * contour_error;
  const double e = position - desired + delta_eps;   // eq. 16
  s_ = sliding_.sliding_variable(e, previous_error_);  // eq. 17
  const double phi = estimator_.phi();
  // eq. 24, with H = lambda(k) = 0 and eps(k+1) ~ eps(k)
  const double equivalent =
      (sliding_.next_sliding_variable(s_) / g.lambda1 + (1.0 - g.beta) * e -
       g.lambda2 / g.lambda1 * signed_power(e, g.alpha) - estimator_.psi() * estimator_.disturbance_increment() +
       desired_next - delta_eps - position) /
      phi;
  const double switching = -gains_.switching_gain * sign(s_) / phi;  // eq. 25
  const double increment = equivalent + switching;
  const double u = previous_command_ + increment;
  previous_position_ = position;
  previous_error_ = e;
  previous_command_ = u;
  previous_increment_ = increment;
  return u;
}

std::unique_ptr<DataDrivenAxisLaw> MfaDtsmcAxis::clone() const { return std::make_unique<MfaDtsmcAxis>(*this); }

std::string MfaDtsmcAxis::describe() const {
  std::ostringstream out;
  out << "MFA-DTSMC(" << sliding_.describe() << ", lambda_s=" << gains_.switching_gain
      << ", delta=" << gains_.contour_weight << "; " << estimator_.describe() << ")";
  return out.str();
}

NamedEstimate MfaDtsmcAxis::estimate(std::size_t index) const {
  switch (index) {
    case 0: return {"phi_hat", "um/V", estimator_.phi()};
    case 1: return {"psi_hat", "um/V", estimator_.psi()};
    case 2: return {"disturbance_increment_hat", "V", estimator_.disturbance_increment()};
    case 3: return {"disturbance_hat", "V", estimator_.disturbance()};
    default: return {"sliding_variable", "um", s_};
  }
}

}  // namespace netmc::control
