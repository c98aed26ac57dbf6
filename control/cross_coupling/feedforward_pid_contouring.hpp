#pragma once
// Paper 004's cross-coupled structure (section 2.2, derived from eq. 6): per axis the feedback G_c
// of eq. 2 with the acceleration feedforward (FeedforwardPidAxis), and a cross-coupling law C on
// the estimated contour error, distributed with the sign convention of paper 001's eq. 15:
//   ε_c = E_y cos φ - E_x sin φ (eq. 3 with the tangent estimator), u_c = C ε_c,
//   U_x = u_x - C_x u_c,  U_y = u_y + C_y u_c,  C_x = sin φ, C_y = cos φ (eq. 4), E = r - y.
// Unlike ContouringController its axes see the reference acceleration (the feedforward).
// φ is the tangent of the desired path. A reference at rest (a stop at a corner, the hold after
// the end) has no velocity to take it from; the path's tangent there is the direction it
// arrived in, so the estimator then sees the last direction of travel.

#include <memory>
#include <string>

#include "control/axis/feedforward_pid_axis.hpp"
#include "control/contouring/contour_controller.hpp"
#include "control/contour_error/contour_error_estimator.hpp"
#include "control/cross_coupling/contour_compensator.hpp"

namespace netmc::control {

class FeedforwardPidContouring final : public ContourController {
 public:
  FeedforwardPidContouring(const FeedforwardPidGains& x_axis, const FeedforwardPidGains& y_axis,
                           double sample_period_s, std::unique_ptr<ContourErrorEstimator> estimator,
                           std::unique_ptr<ContourCompensator> compensator);

  void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples) override;
  ContouringCycle step(std::size_t cycle, const ReferencePoint& reference, const Eigen::Vector2d& measured) override;
  void end_iteration() override;
  std::string describe() const override;

  const FeedforwardPidAxis& axis(int index) const { return axes_[index]; }
  const ContourCompensator& compensator() const { return *compensator_; }

 private:
  // The reference as the estimator sees it: itself while moving; at rest, moving at unit speed
  // along the last direction of travel without acceleration (a straight path there).
  const ReferencePoint& along_path(const ReferencePoint& reference);

  FeedforwardPidAxis axes_[2];
  std::unique_ptr<ContourErrorEstimator> estimator_;
  std::unique_ptr<ContourCompensator> compensator_;
  ReferencePoint at_rest_;
  bool travelled_ = false;  // a direction of travel has been seen this iteration
};

}  // namespace netmc::control
