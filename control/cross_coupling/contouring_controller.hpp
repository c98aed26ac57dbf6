#pragma once
// A per-axis controller for each axis composed with a contour-error estimator and a contour
// compensator (paper 001, eq. 15): U_x = u_x - cx*u_e, U_y = u_y + cy*u_e.

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "control/axis/axis_controller.hpp"
#include "control/contouring/contour_controller.hpp"
#include "control/cross_coupling/contour_compensator.hpp"
#include "control/contour_error/contour_error_estimator.hpp"
#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

class ContouringController final : public ContourController {
 public:
  ContouringController(std::unique_ptr<AxisController> x_axis,
                       std::unique_ptr<AxisController> y_axis,
                       std::unique_ptr<ContourErrorEstimator> estimator,
                       std::unique_ptr<ContourCompensator> compensator);
  ContouringController(const ContouringController& other);
  ContouringController& operator=(const ContouringController&) = delete;

  // Start of an iteration with the axes at rest at `initial_position`, `samples` cycles long.
  void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples) override;
  // Cycle k: reference point and measured axis positions in, commands out (paper 001, eq. 8-15).
  ContouringCycle step(std::size_t cycle, const ReferencePoint& reference,
                       const Eigen::Vector2d& measured) override;
  void end_iteration() override;

  std::string describe() const override;
  std::unique_ptr<ContourController> clone() const override { return std::make_unique<ContouringController>(*this); }
  const ContourCompensator& compensator() const { return *compensator_; }

 private:
  std::unique_ptr<AxisController> axes_[2];
  std::unique_ptr<ContourErrorEstimator> estimator_;
  std::unique_ptr<ContourCompensator> compensator_;
};

}  // namespace netmc::control
