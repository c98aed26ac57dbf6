#pragma once
// A contour group of n axes as the job runner drives it each cycle, whatever its dimension: the
// reference and exact contour it follows (GroupContour) and the controller that closes its loops
// (GroupController). Two-axis groups wrap the planar trajectories and controllers
// (planar_contour_group.hpp), three-axis groups the circle in space and GTCF-SARC
// (spatial_contour_group.hpp), one-axis groups a tracking reference and a tracking controller
// (single_axis_group.hpp). Vectors have a fixed capacity so that a cycle never allocates.
// See docs/architecture.md, "One cycle through the code".

#include <Eigen/Dense>
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "control/contour_error/contour_error_estimator.hpp"
#include "control/controller_estimate.hpp"

namespace netmc::control {

inline constexpr int kMaxGroupAxes = 8;
// One value per axis of the group, x first.
using AxisVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxGroupAxes, 1>;

struct GroupReference {
  AxisVector position, velocity, acceleration;
  double time_s = 0.0;
};

// A reference point of fixed dimension (planar, spatial) into the group's form.
template <class Point>
void assign_reference(const Point& point, GroupReference& out) {
  out.position = point.position;
  out.velocity = point.velocity;
  out.acceleration = point.acceleration;
}

class GroupContour {
 public:
  virtual ~GroupContour() = default;
  virtual std::size_t axes() const = 0;
  // The desired point at `time_s` (written into `out`, sized to axes()).
  virtual void sample(double time_s, GroupReference& out) const = 0;
  // The ground truth of the metrics for `point` in the cycle whose desired point is `reference`:
  // the exact distance to the contour for two or more axes (signed where the contour has sides,
  // planar; >= 0 otherwise; `reference` unused), the tracking error x - x_d for one axis.
  virtual double contour_error(const AxisVector& point, const GroupReference& reference) const = 0;
  virtual double duration_s() const = 0;
  // One pass of a repeating reference (a revolution); the whole run otherwise.
  virtual double period_s() const = 0;
  virtual std::string describe() const = 0;
};

struct GroupCycle {
  AxisVector command;                 // U, sent to the axes
  AxisVector axis_command;            // u of the per-axis controllers (U where there are none)
  double coupling_command = 0.0;      // u_e of a cross-coupled controller, else 0
  ContourErrorEstimate estimate;      // the controller's own contour-error estimate
  // The controller's internal estimates (GroupController::estimate_names), the rest unused.
  std::array<double, kMaxControllerEstimates> estimates{};
};

class GroupController {
 public:
  virtual ~GroupController() = default;
  // Start of an iteration with the axes at rest at `initial_position`, `samples` cycles long.
  virtual void begin_iteration(const AxisVector& initial_position, std::size_t samples) = 0;
  // Cycle k: reference point and measured axis positions in, commands out (valid until the
  // next call).
  virtual const GroupCycle& step(std::size_t cycle, const GroupReference& reference,
                                 const AxisVector& measured) = 0;
  virtual void end_iteration() {}
  virtual std::string describe() const = 0;
  // Names and units of GroupCycle::estimates, fixed for the controller's life.
  virtual std::vector<EstimateName> estimate_names() const { return {}; }
  // A copy in the same state, to run ahead of the loop on predicted positions (packetized
  // predictive control); none for a law that cannot be copied.
  virtual std::unique_ptr<GroupController> clone() const { return nullptr; }
};

}  // namespace netmc::control
