#pragma once
// A dead-zone inverse between any group controller and its axes (thesis, paper 000, section 5.5):
// each axis's dead zone, identified beforehand (e.g. by a single-axis axis-diarc-dead-zone run),
// is inverted by eq. 5-4 with its estimate held fixed, so the contouring controller designed as
// in chapters 3 and 4 sees drives without a gap. The controller keeps its own command u as the
// plant's input (its estimators are unchanged); the axes receive v = D^-1(u).

#include <memory>
#include <vector>

#include "control/group/contour_group.hpp"
#include "control/dead_zone/dead_zone_inverse.hpp"

namespace netmc::control {

class DeadZoneCompensatedGroup final : public GroupController {
 public:
  // One estimate per axis of the group, in order (checked by the caller against the group;
  // each validated here: std::invalid_argument "controller.dead_zone_inverse[i]...").
  DeadZoneCompensatedGroup(std::unique_ptr<GroupController> inner, std::vector<DeadZoneEstimate> dead_zones);

  void begin_iteration(const AxisVector& initial_position, std::size_t samples) override;
  const GroupCycle& step(std::size_t cycle, const GroupReference& reference, const AxisVector& measured) override;
  void end_iteration() override { inner_->end_iteration(); }
  std::string describe() const override;
  std::vector<EstimateName> estimate_names() const override { return inner_->estimate_names(); }

 private:
  std::unique_ptr<GroupController> inner_;
  std::vector<DeadZoneEstimate> dead_zones_;
  std::vector<DeadZoneInverse> inverses_;
  GroupCycle cycle_;
};

}  // namespace netmc::control
