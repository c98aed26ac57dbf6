#pragma once
// One-axis groups (thesis, paper 000, ch. 5): a tracking reference and a tracking controller seen
// through the n-axis group interfaces, so that single-axis experiments run in the same job runner
// as the contouring ones. The group's "contour error" is the tracking error x - x_d; its RMS and
// maximum are the thesis's ||x~||_2 and ||x~||_inf (Table 5-1).

#include <memory>
#include <string_view>

#include "control/axis/tracking_controller.hpp"
#include "control/group/contour_group.hpp"
#include "control/trajectory/multi_sine_reference.hpp"

namespace netmc::control {

class SingleAxisTrack final : public GroupContour {
 public:
  // Throws std::invalid_argument for a missing reference.
  explicit SingleAxisTrack(std::shared_ptr<const MultiSineReference> reference);

  std::size_t axes() const override { return 1; }
  void sample(double time_s, GroupReference& out) const override;
  double contour_error(const AxisVector& point, const GroupReference& reference) const override;
  double duration_s() const override { return reference_->duration_s(); }
  double period_s() const override { return reference_->period_s(); }
  std::string describe() const override { return reference_->describe(); }

 private:
  std::shared_ptr<const MultiSineReference> reference_;
};

class TrackingGroupController final : public GroupController {
 public:
  explicit TrackingGroupController(std::unique_ptr<TrackingController> controller);

  void begin_iteration(const AxisVector& initial_position, std::size_t samples) override;
  const GroupCycle& step(std::size_t cycle, const GroupReference& reference,
                         const AxisVector& measured) override;
  std::string describe() const override { return controller_->describe(); }
  std::vector<EstimateName> estimate_names() const override { return controller_->estimate_names(); }

 private:
  std::unique_ptr<TrackingController> controller_;
  bool has_estimates_ = false;
  GroupCycle cycle_;
};

}  // namespace netmc::control
