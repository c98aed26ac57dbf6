#pragma once
// Paper 002's contouring structure: a data-driven law per axis (MFA-DTSMC, CFDL-MFAC) that takes
// its own component of the estimated contour-error vector into its error (eq. 16), with the
// contour error from any in-loop estimator (tangent, curvature, Newton, Steffensen). The laws run
// in `length_unit_m` (paper 002's gains are for um, digest 3.7 [A]); commands are in volts.

#include <memory>

#include "control/contour_controller.hpp"
#include "control/contour_error/contour_error_estimator.hpp"
#include "control/data_driven/data_driven_axis_law.hpp"

namespace netmc::control {

class DataDrivenContouring final : public ContourController {
 public:
  DataDrivenContouring(std::unique_ptr<DataDrivenAxisLaw> x_axis, std::unique_ptr<DataDrivenAxisLaw> y_axis,
                       std::unique_ptr<ContourErrorEstimator> estimator, double sample_period_s,
                       double length_unit_m = 1e-6);
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
};

}  // namespace netmc::control
