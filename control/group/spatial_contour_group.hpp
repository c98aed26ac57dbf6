#pragma once
// Three-axis contour groups (thesis, paper 000, ch. 6): the circle in space and GTCF-SARC seen
// through the n-axis group interfaces.

#include <memory>
#include <string_view>

#include "control/group/contour_group.hpp"
#include "control/trajectory/spatial_circle.hpp"
#include "control/task_space/spatial_sarc.hpp"

namespace netmc::control {

class SpatialContour final : public GroupContour {
 public:
  // The run is `duration_s` of uniform motion along the circle. Throws std::invalid_argument for
  // a missing circle or a non-positive duration.
  SpatialContour(std::shared_ptr<const SpatialCircle> circle, double duration_s);

  std::size_t axes() const override { return 3; }
  void sample(double time_s, GroupReference& out) const override;
  double contour_error(const AxisVector& point, const GroupReference& reference) const override;  // >= 0
  double duration_s() const override { return duration_s_; }
  double period_s() const override { return circle_->period_s(); }
  std::string describe() const override { return circle_->describe(); }
  const std::shared_ptr<const SpatialCircle>& circle() const { return circle_; }

 private:
  std::shared_ptr<const SpatialCircle> circle_;
  double duration_s_;
};

class SpatialSarcGroupController final : public GroupController {
 public:
  SpatialSarcGroupController(const SpatialSarcGains& gains, double sample_period_s,
                             std::shared_ptr<const SpatialCircle> circle);

  void begin_iteration(const AxisVector& initial_position, std::size_t samples) override;
  const GroupCycle& step(std::size_t cycle, const GroupReference& reference,
                         const AxisVector& measured) override;
  std::string describe() const override;

 private:
  SpatialSarcGains gains_;
  SpatialSarc controller_;
  GroupCycle cycle_;
};

}  // namespace netmc::control
