#pragma once
// Model-free adaptive control (paper 002's comparison controller C3, whose law the paper does not
// print: netmc assumes the standard CFDL-MFAC law [A]) with the contour error folded into the error
// it drives to zero.
// data_model compact (paper 002, eq. 9; the default):
//   Phi^(k) = Phi^(k-1) + eta du(k-1) (dy(k) - Phi^(k-1) du(k-1)) / (mu + du(k-1)^2)
//   reset to Phi^(1) when |Phi^| <= epsilon, |du(k-1)| <= epsilon or sign(Phi^) != sign(Phi^(1))
//   u(k)    = u(k-1) - rho Phi^(k) E / (lambda + Phi^(k)^2),  E = y(k) - y_d(k+1) + delta eps
// data_model full: a full-form (L_y = 2, d = 1) data model, not the paper's compact form
// (FullFormDataModel, with this law's eta, mu, epsilon and Phi^(1) as b0(1)); the same step on
// E = y^(k+2 | du(k) = 0) - y_d(k+2) + delta eps with gain b0^.
// Per axis (command()) eps is eps(k); DataDrivenContouring writes eps at the target sample
// through the outputs and solves the step for both axes together (eq. 24's coupling).

#include "control/data_driven/data_driven_axis_law.hpp"
#include "control/data_driven/data_model_estimator.hpp"

namespace netmc::control {

// Paper 002, section 6.3, C3; lengths in um.
struct CompactFormMfacGains {
  double mu = 0.5, lambda = 0.1, rho = 0.6, eta = 1.0, epsilon = 1e-5;
  double phi_initial = 18.0;     // um/V
  double contour_weight = 20.0;  // delta
  DataModelForm data_model = DataModelForm::compact;
};

class CompactFormMfacAxis final : public DataDrivenAxisLaw {
 public:
  explicit CompactFormMfacAxis(const CompactFormMfacGains& gains);

  void reset(double position) override;
  AxisPrediction predict(double position, double desired, double desired_next, double desired_after,
                         double contour_error) override;
  double commit(double increment) override;
  std::unique_ptr<DataDrivenAxisLaw> clone() const override;
  std::string describe() const override;
  std::size_t estimate_count() const override { return gains_.data_model == DataModelForm::full ? 3 : 1; }
  NamedEstimate estimate(std::size_t index) const override;

 private:
  CompactFormMfacGains gains_;
  FullFormDataModel full_;
  double phi_ = 0.0, previous_position_ = 0.0, previous_command_ = 0.0, previous_increment_ = 0.0;
};

}  // namespace netmc::control
