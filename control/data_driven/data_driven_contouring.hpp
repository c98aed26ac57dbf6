#pragma once
// Paper 002's contouring structure: a data-driven law per axis (MFA-DTSMC, CFDL-MFAC) that takes
// its own component of the estimated contour-error vector into its error (eq. 16), with the
// contour error from any in-loop estimator (tangent, curvature, Newton, Steffensen). The laws run
// in `length_unit_m` (netmc assumes paper 002's gains are for um [A]); commands are in volts.
//
// Contour coupling (fills a gap of paper 002): eq. 24 needs eps(k+1), the contour error one sample
// ahead, which depends on the increments being chosen; the per-axis eps(k+1) ~ eps(k) makes both
// laws unstable even on a plant that is exactly their data model. With n the unit normal of the
// contour-error estimate (eps = n n^T (P - foot point), the foot point and the reference moving
// along the tangent to first order), eps(k+1) = eps(k) + n n^T (e_tr(k+1) - e_tr(k)) with
// e_tr = y - y_d, so the composite error of eq. 16 at the target sample is
//   E(k+1) = (I + D n n^T) e_tr(k+1) + D (eps(k) - n n^T e_tr(k)),   D = diag(delta_x, delta_y),
// linear in both axes' du(k) through e_tr(k+1) = free error + diag(gain) du(k). ContourCoupling::
// through_outputs (the default) solves that 2x2 system: C4 puts E at its reaching-law target,
// C3 takes MFAC's penalised least-squares step on E. ContourCoupling::frozen is the per-axis law
// with eps(k+1) ~ eps(k) (n = 0).

#include <memory>

#include "control/contouring/contour_controller.hpp"
#include "control/contour_error/contour_error_estimator.hpp"
#include "control/data_driven/data_driven_axis_law.hpp"

namespace netmc::control {

enum class ContourCoupling { through_outputs, frozen };

// The joint increments for both axes (see above); `normal` is the unit normal (0 for frozen).
// Throws std::logic_error when the two predictions ask for different rules.
Eigen::Vector2d coupled_increments(const AxisPrediction& x, const AxisPrediction& y, const Eigen::Vector2d& normal);

class DataDrivenContouring final : public ContourController {
 public:
  DataDrivenContouring(std::unique_ptr<DataDrivenAxisLaw> x_axis, std::unique_ptr<DataDrivenAxisLaw> y_axis,
                       std::unique_ptr<ContourErrorEstimator> estimator, double sample_period_s,
                       double length_unit_m = 1e-6, ContourCoupling coupling = ContourCoupling::through_outputs);
  DataDrivenContouring(const DataDrivenContouring& other);
  DataDrivenContouring& operator=(const DataDrivenContouring&) = delete;

  void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples) override;
  ContouringCycle step(std::size_t cycle, const ReferencePoint& reference, const Eigen::Vector2d& measured) override;
  std::string describe() const override;
  // Each axis's law estimates, x first ("x_phi_hat" ...).
  std::vector<EstimateName> estimate_names() const override;
  void read_estimates(double* out) const override;
  const DataDrivenAxisLaw& axis(int index) const { return *axes_[index]; }

 private:
  std::unique_ptr<DataDrivenAxisLaw> axes_[2];
  std::unique_ptr<ContourErrorEstimator> estimator_;
  double h_;
  double scale_;  // controller units per metre
  ContourCoupling coupling_;
};

}  // namespace netmc::control
