#pragma once
// The part of the thesis's task-space contouring controllers (paper 000, SARC eq. 2-50..2-60,
// DARC/DIARC eq. 3-15..3-23) that does not depend on how the model is adapted: velocity from
// measured positions, the task-frame error e, the sliding variable s = e' + Lambda e and the
// equivalent motion q_eq' = J^-1 r_eq', q_eq''.
// In the global task frame (GTCF) e = r(q) - r_d with r = [rc, rm] and J = dr/dq; in the local
// task frame (LTCF, eq. 2-61..2-64) e = T(alpha) (q - q_d) and J = T, the frame of the tangent at
// the desired point. In the GTCF the reference may pass through the trajectory initialization
// filter (eq. 2-67): r_d is replaced by r_i = r_d + z.
// Velocity is differenced from measured positions (as on the thesis stage) with the second-order
// backward difference: the plain one lags half a period, and on a fast curve its direction then
// leans off the tangent and reads as a contour velocity. q_eq'' is the difference of q_eq' over
// one period.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "control/trajectory/reference_trajectory.hpp"
#include "control/task_space/task_frame.hpp"
#include "control/task_space/trajectory_initialization_filter.hpp"

namespace netmc::control {

// How the local task frame's error is differentiated (LTCF only; the GTCF ignores it).
enum class LocalFrameRate {
  frozen,    // e' = T (q' - q_d'): T(alpha) held over the sample, as eq. 2-63 reads
  rotating,  // e' = T (q' - q_d') + T' (q - q_d): the frame turns with the desired tangent
};

struct SlidingState {
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();                 // q' (differenced)
  Eigen::Vector2d error = Eigen::Vector2d::Zero();                    // e, [contour, tangential]
  Eigen::Matrix2d jacobian = Eigen::Matrix2d::Identity();             // J
  Eigen::Matrix2d inverse = Eigen::Matrix2d::Identity();              // J^-1
  Eigen::Vector2d s = Eigen::Vector2d::Zero();                        // eq. 2-50 / 3-15
  Eigen::Vector2d equivalent_acceleration = Eigen::Vector2d::Zero();  // q_eq''
};

class TaskSpaceSlidingVariable {
 public:
  // Global frame: `frame` of the contour. Local frame: frame == nullptr (no initialization
  // filter there). Throws std::invalid_argument naming the setting when one is invalid.
  TaskSpaceSlidingVariable(const Eigen::Vector2d& lambda, double sample_period_s,
                           std::shared_ptr<const TaskFrame> frame,
                           const InitializationFilterSettings& filter,
                           LocalFrameRate local_rate = LocalFrameRate::frozen);

  void reset();
  // Once per cycle, in order: the reference and the measured position of cycle k.
  SlidingState update(std::size_t cycle, const ReferencePoint& reference, const Eigen::Vector2d& q);

  bool global() const { return frame_ != nullptr; }
  bool filtered() const { return filter_.has_value(); }
  const char* frame_name() const { return frame_ ? "gtcf" : "ltcf"; }
  std::string filter_description() const;  // ", init filter wc=.. wm=.." or empty

 private:
  Eigen::Vector2d lambda_;
  double h_;
  std::shared_ptr<const TaskFrame> frame_;
  LocalFrameRate local_rate_;
  std::optional<TrajectoryInitializationFilter> filter_;
  InitializationFilterSettings filter_settings_;
  std::size_t first_cycle_ = 0;
  Eigen::Vector2d previous_position_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d earlier_position_ = Eigen::Vector2d::Zero();  // two samples back
  int samples_seen_ = 0;
  Eigen::Vector2d previous_equivalent_velocity_ = Eigen::Vector2d::Zero();
  double desired_rm_ = 0.0;  // rm of the previous reference, where the next is sought
};

}  // namespace netmc::control
