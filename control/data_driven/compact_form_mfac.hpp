#pragma once
// Compact-form model-free adaptive control (paper 002's comparison controller C3, digest 3.7 [A]:
// the standard CFDL-MFAC law) with the contour error folded into the target:
//   Phi^(k) = Phi^(k-1) + eta du(k-1) (dy(k) - Phi^(k-1) du(k-1)) / (mu + du(k-1)^2)
//   reset to Phi^(1) when |Phi^| <= epsilon, |du(k-1)| <= epsilon or sign(Phi^) != sign(Phi^(1))
//   u(k)    = u(k-1) + rho Phi^(k) (y*(k+1) - y(k)) / (lambda + Phi^(k)^2),  y* = y_d - delta eps

#include "control/data_driven/data_driven_axis_law.hpp"

namespace netmc::control {

// Paper 002, sec. 5, C3 (digest 3.6); lengths in um.
struct CompactFormMfacGains {
  double mu = 0.5, lambda = 0.1, rho = 0.6, eta = 1.0, epsilon = 1e-5;
  double phi_initial = 18.0;     // um/V
  double contour_weight = 20.0;  // delta
};

class CompactFormMfacAxis final : public DataDrivenAxisLaw {
 public:
  explicit CompactFormMfacAxis(const CompactFormMfacGains& gains);

  void reset(double position) override;
  double command(double position, double desired, double desired_next, double contour_error) override;
  std::unique_ptr<DataDrivenAxisLaw> clone() const override;
  std::string describe() const override;
  std::size_t estimate_count() const override { return 1; }
  NamedEstimate estimate(std::size_t) const override { return {"phi_hat", "um/V", phi_}; }

 private:
  CompactFormMfacGains gains_;
  double phi_ = 0.0, previous_position_ = 0.0, previous_command_ = 0.0, previous_increment_ = 0.0;
};

}  // namespace netmc::control
