#include "control/group/dead_zone_compensated_group.hpp"

#include <sstream>
#include <stdexcept>
#include <string>

namespace netmc::control {

DeadZoneCompensatedGroup::DeadZoneCompensatedGroup(std::unique_ptr<GroupController> inner,
                                                   std::vector<DeadZoneEstimate> dead_zones)
    : inner_(std::move(inner)), dead_zones_(std::move(dead_zones)), inverses_(dead_zones_.size()) {
  if (!inner_) throw std::invalid_argument("controller: missing");
  for (std::size_t i = 0; i < dead_zones_.size(); ++i) {
    dead_zones_[i].validate("controller.dead_zone_inverse[" + std::to_string(i) + "]");
  }
}

void DeadZoneCompensatedGroup::begin_iteration(const AxisVector& initial_position, std::size_t samples) {
  for (auto& inverse : inverses_) inverse.reset();
  inner_->begin_iteration(initial_position, samples);
}

const GroupCycle& DeadZoneCompensatedGroup::step(std::size_t cycle, const GroupReference& reference,
                                                 const AxisVector& measured) {
  cycle_ = inner_->step(cycle, reference, measured);
  for (std::size_t i = 0; i < inverses_.size(); ++i) {
    const auto axis = static_cast<Eigen::Index>(i);
    cycle_.command[axis] = inverses_[i].invert(cycle_.command[axis], dead_zones_[i]);  // thesis (5-4)
  }
  return cycle_;
}

std::string DeadZoneCompensatedGroup::describe() const {
  std::ostringstream text;
  text << inner_->describe() << "; dead-zone inverse";
  for (std::size_t i = 0; i < dead_zones_.size(); ++i) {
    const auto& d = dead_zones_[i];
    text << (i == 0 ? " " : ", ") << "[b_r " << d.right_break() << ", b_l " << d.left_break() << ", m_r "
         << d.right_slope << ", m_l " << d.left_slope << "]";
  }
  return text.str();
}

}  // namespace netmc::control
