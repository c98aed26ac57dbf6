#pragma once
// Simple adaptive robust contouring control in task coordinates (thesis, paper 000, eq. 2-50 to
// 2-60): s = e_dot + Lambda e, model compensation M q_eq'' + B q' + A S_f(q'), the lumped
// uncertainty F_l estimated with projection into |F_l| <= F_M, robust feedback -J^T K_s s.
// e, s, J and q_eq'' in the global (GTCF) or local (LTCF) task frame: TaskSpaceSlidingVariable.

#include <memory>

#include "control/contouring/contour_controller.hpp"
#include "control/task_space/task_space_sliding_variable.hpp"

namespace netmc::control {

struct SarcGains {
  Eigen::Vector2d mass{0.1, 0.55};           // M [V/(m/s^2)], thesis ch. 2 nominal
  Eigen::Vector2d damping{0.4, 0.5};         // B [V/(m/s)]
  Eigen::Vector2d coulomb{0.1, 0.15};        // A [V]
  double friction_slope = 9000.0;            // S_f(v) = 2/pi atan(slope v)
  Eigen::Vector2d lambda{100.0, 30.0};       // Lambda = diag(contour, tangential)
  Eigen::Vector2d feedback{100.0, 60.0};     // K_s
  Eigen::Vector2d adaptation{1e4, 1e4};      // Gamma
  Eigen::Vector2d uncertainty_bound{1.5, 1.5};  // F_M [V]
};

class TaskSpaceSarc final : public ContourController {
 public:
  // Global frame: `frame` of the contour. Local frame: frame == nullptr. The initialization
  // filter (eq. 2-67) needs the global frame.
  TaskSpaceSarc(const SarcGains& gains, double sample_period_s, std::shared_ptr<const TaskFrame> frame,
                const InitializationFilterSettings& filter = {},
                LocalFrameRate local_rate = LocalFrameRate::frozen);

  void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples) override;
  ContouringCycle step(std::size_t cycle, const ReferencePoint& reference,
                       const Eigen::Vector2d& measured) override;
  std::string describe() const override;

  const Eigen::Vector2d& uncertainty_estimate() const { return estimate_; }

 private:
  SarcGains gains_;
  double h_;
  TaskSpaceSlidingVariable sliding_;
  Eigen::Vector2d estimate_ = Eigen::Vector2d::Zero();  // F_l hat
};

}  // namespace netmc::control
