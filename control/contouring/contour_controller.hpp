#pragma once
// A controller of a two-axis contour group, as the job runner drives it each cycle: the
// composition of per-axis loops with contour compensation (ContouringController) or a
// task-space contouring controller (TaskSpaceSarc).

#include <Eigen/Dense>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "control/contour_error/contour_error_estimator.hpp"
#include "control/controller_estimate.hpp"
#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

struct ContouringCycle {
  Eigen::Vector2d command = Eigen::Vector2d::Zero();       // U, sent to the axes
  Eigen::Vector2d axis_command = Eigen::Vector2d::Zero();  // u of the per-axis controllers
  double coupling_command = 0.0;                           // u_e
  ContourErrorEstimate estimate;
};

class ContourController {
 public:
  virtual ~ContourController() = default;
  // Start of an iteration with the axes at rest at `initial_position`, `samples` cycles long.
  virtual void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples) = 0;
  // Cycle k: reference point and measured axis positions in, commands out.
  virtual ContouringCycle step(std::size_t cycle, const ReferencePoint& reference,
                               const Eigen::Vector2d& measured) = 0;
  virtual void end_iteration() {}
  virtual std::string describe() const = 0;
  // Internal estimates in a fixed order (at most kMaxControllerEstimates); none by default.
  virtual std::vector<EstimateName> estimate_names() const { return {}; }
  // Their values after the last step(), into out[0 .. estimate_names().size()). No allocation.
  virtual void read_estimates(double* /*out*/) const {}
  // A copy in the same state, to run ahead of the loop on predicted positions (packetized
  // predictive control); none for a law that cannot be copied.
  virtual std::unique_ptr<ContourController> clone() const { return nullptr; }
};

}  // namespace netmc::control
