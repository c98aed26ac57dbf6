#pragma once
// Paper 002's per-axis law C4, model-free adaptive discrete terminal sliding mode control with
// contour coupling (eq. 16-25; the combined law, eq. 26-28, is missing from the source text),
// implemented with netmc's assumptions [A]: the estimation errors H and lambda(k) are unknown and
// taken as 0, and, per axis (command()), eps(k+1) ~ eps(k):
//   e(k)   = y(k) - y_d(k) + delta eps(k)                                            (eq. 16)
//   du_eq  = [ (E1 s - E2 sgn s)/lambda1 + (1 - beta) e(k) - (lambda2/lambda1) e(k)^alpha
//              - Psi^ dd^(k) + y_d(k+1) - delta eps(k) - y(k) ] / Phi^                  (eq. 24)
//   du_sw  = -lambda_s sgn s(k) / Phi^                                                 (eq. 25)
//   u(k)   = u(k-1) + du_eq + du_sw
// with Phi^, Psi^ and dd^ from DataModelEstimator (eq. 11-14). In DataDrivenContouring the law
// gives the target e(k+1) = s(k+1)/lambda1 + (1 - beta) e(k) - (lambda2/lambda1) e(k)^alpha
// - lambda_s sgn s(k) and the composition writes eps(k+1) through y(k+1) (eq. 24's coupling).
// data_model full: a full-form (L_y = 2, d = 1) data model, not the paper's compact form
// (FullFormDataModel with the estimator's eta, mu, epsilon and Phi(1) as b0(1); Psi^, dd^ as
// above on its residual). du(k) first moves y(k+2), so eq. 17-24 are taken one sample later: e(k)
// is the free-response prediction y^(k+1) - y_d(k+1) + delta eps(k), e(k-1) the measured e(k),
// and the target is the composite error at k+2 with gain b0^.

#include "control/data_driven/data_driven_axis_law.hpp"
#include "control/data_driven/data_model_estimator.hpp"
#include "control/data_driven/terminal_sliding_mode.hpp"

namespace netmc::control {

// Paper 002, section 6.3, C4; lengths in um (netmc's assumption [A]).
struct MfaDtsmcGains {
  DataModelEstimatorGains estimator;
  TerminalSlidingModeGains sliding;
  double switching_gain = 0.5;   // lambda_s
  double contour_weight = 20.0;  // delta of eq. 16
  DataModelForm data_model = DataModelForm::compact;
};

class MfaDtsmcAxis final : public DataDrivenAxisLaw {
 public:
  MfaDtsmcAxis(const MfaDtsmcGains& gains, double sample_period_s);

  void reset(double position) override;
  AxisPrediction predict(double position, double desired, double desired_next, double desired_after,
                         double contour_error) override;
  double commit(double increment) override;
  std::unique_ptr<DataDrivenAxisLaw> clone() const override;
  std::string describe() const override;
  std::size_t estimate_count() const override { return gains_.data_model == DataModelForm::full ? 7 : 5; }
  NamedEstimate estimate(std::size_t index) const override;

  const DataModelEstimator& data_model() const { return estimator_; }
  double sliding_variable() const { return s_; }

 private:
  MfaDtsmcGains gains_;
  DataModelEstimator estimator_;
  FullFormDataModel full_;
  TerminalSlidingMode sliding_;
  double previous_position_ = 0.0, previous_error_ = 0.0;
  double previous_command_ = 0.0, previous_increment_ = 0.0;
  double s_ = 0.0;
};

}  // namespace netmc::control
