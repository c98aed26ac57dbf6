#pragma once
// Two-axis contour groups: a planar trajectory and any planar contouring controller
// (server/job/controllers/) seen through the n-axis group interfaces, values unchanged.

#include <memory>
#include <string_view>

#include "control/contouring/contour_controller.hpp"
#include "control/group/contour_group.hpp"
#include "control/trajectory/reference_trajectory.hpp"

namespace netmc::control {

class PlanarContour final : public GroupContour {
 public:
  explicit PlanarContour(std::shared_ptr<const ReferenceTrajectory> trajectory);

  std::size_t axes() const override { return 2; }
  void sample(double time_s, GroupReference& out) const override;
  double contour_error(const AxisVector& point, const GroupReference& reference) const override;
  double duration_s() const override { return trajectory_->duration_s(); }
  double period_s() const override { return trajectory_->period_s(); }
  std::string describe() const override { return trajectory_->describe(); }
  const ReferenceTrajectory& trajectory() const { return *trajectory_; }

 private:
  std::shared_ptr<const ReferenceTrajectory> trajectory_;
};

class PlanarGroupController final : public GroupController {
 public:
  explicit PlanarGroupController(std::unique_ptr<ContourController> controller);

  void begin_iteration(const AxisVector& initial_position, std::size_t samples) override;
  const GroupCycle& step(std::size_t cycle, const GroupReference& reference,
                         const AxisVector& measured) override;
  void end_iteration() override { controller_->end_iteration(); }
  std::string describe() const override { return controller_->describe(); }
  std::vector<EstimateName> estimate_names() const override { return controller_->estimate_names(); }
  std::unique_ptr<GroupController> clone() const override;

 private:
  std::unique_ptr<ContourController> controller_;
  bool has_estimates_ = false;
  GroupCycle cycle_;
};

}  // namespace netmc::control
