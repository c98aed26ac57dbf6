#pragma once
// A per-axis controller for each axis composed with a contour-error estimator and a contour
// compensator (paper 001, eq. 15): U_x = u_x - cx*u_e, U_y = u_y + cy*u_e.

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "control/axis_controller.hpp"
#include "control/contour_compensator.hpp"
#include "control/contour_error_estimator.hpp"
#include "control/reference_trajectory.hpp"

namespace netmc::control {

struct ContouringCycle {
  Eigen::Vector2d command = Eigen::Vector2d::Zero();       // U, sent to the axes
  Eigen::Vector2d axis_command = Eigen::Vector2d::Zero();  // u of the per-axis controllers
  double coupling_command = 0.0;                           // u_e
  ContourErrorEstimate estimate;
};

class ContouringController {
 public:
  ContouringController(std::unique_ptr<AxisController> x_axis,
                       std::unique_ptr<AxisController> y_axis,
                       std::unique_ptr<ContourErrorEstimator> estimator,
                       std::unique_ptr<ContourCompensator> compensator);
  ContouringController(const ContouringController& other);
  ContouringController& operator=(const ContouringController&) = delete;

  // Start of an iteration with the axes at rest at `initial_position`, `samples` cycles long.
  void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples);
  // Cycle k: reference point and measured axis positions in, commands out (paper 001, sec. 1.5).
  ContouringCycle step(std::size_t cycle, const ReferencePoint& reference,
                       const Eigen::Vector2d& measured);
  void end_iteration();

  std::string describe() const;
  const ContourCompensator& compensator() const { return *compensator_; }

 private:
  std::unique_ptr<AxisController> axes_[2];
  std::unique_ptr<ContourErrorEstimator> estimator_;
  std::unique_ptr<ContourCompensator> compensator_;
};

}  // namespace netmc::control
