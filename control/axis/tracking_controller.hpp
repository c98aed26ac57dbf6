#pragma once
// A single-axis tracking controller as the job runner drives it each cycle (thesis, paper 000,
// ch. 5: one axis follows x_d(t); the metrics are the tracking error's norms). Unlike
// AxisController, which a contouring law composes with a coupling term, it owns the whole loop:
// reference and measured position in, the axis's input out.

#include <cstddef>
#include <string>
#include <vector>

#include "control/controller_estimate.hpp"
#include "control/trajectory/axis_reference.hpp"

namespace netmc::control {

class TrackingController {
 public:
  virtual ~TrackingController() = default;
  // Start of an iteration with the axis at rest at `initial_position_m`, `samples` cycles long.
  virtual void begin_iteration(double initial_position_m, std::size_t samples) = 0;
  // Cycle k: the command for reference x_d(k) and measured position y(k).
  virtual double step(std::size_t cycle, const AxisReference& reference, double measured_m) = 0;
  virtual std::string describe() const = 0;
  // Internal estimates in a fixed order (at most kMaxControllerEstimates); none by default.
  virtual std::vector<EstimateName> estimate_names() const { return {}; }
  // Their values after the last step(), into out[0 .. estimate_names().size()). No allocation.
  virtual void read_estimates(double* /*out*/) const {}
};

}  // namespace netmc::control
