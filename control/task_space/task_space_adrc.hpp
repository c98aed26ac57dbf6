#pragma once
// Active disturbance rejection in the global task frame (GTCF-ADRC): the thesis's task
// coordinates r = [rc, rm] (paper 000, ch. 2) with paper 001's linear ADRC per task coordinate.
//
// Plant and task coordinates. Cartesian model (thesis eq. 2-43/2-44)
//   M q'' + B q' + A S_f(q') = u - F_l,     M = diag(0.1, 0.55) V/(m/s^2) nominal (ch. 2),
// task coordinates rc (2-11, contour error exact to first order) and rm (2-21, arc length), with
// r' = J q', r'' = J q'' + J' q' (2-45). With the command u = M0 a + B0 q' + A0 S_f(q') the task
// acceleration is r'' = J M^-1 M0 a + J' q' - J M^-1 (model error + F_l).
//
// Extended state per task coordinate i in {c, m} (paper 001, eq. 6/7): each coordinate is a
// double integrator with unit input gain (b0 = 1 in task-acceleration units, m/s^2),
//   r_i'' = u_t,i + f_i,
// where u_t is the commanded task acceleration and f_i the lumped task-space disturbance: mass
// error, friction and cogging the nominal model misses, the coupling of the two coordinates, and
// the command acting late under network delay (paper 001's term b tau (u(k-1) - u(k)) / h in (6)).
// A third-order ESO per coordinate (paper 001, eq. 9; ExtendedStateObserver) estimates
// z1 = r_i, z2 = r_i', z3 = f_i from the measured r_i and the applied u_t,i.
//
// Control (paper 001, eq. 10, with the task reference's own derivatives instead of a TD: r_d is
// analytic here, r_d = [0, rm(q_d)], r_d' = [0, |q_d'|], r_d'' = [0, q_d'.q_d''/|q_d'|]):
//   u_t,i = r_d,i'' + kp_i (r_d,i - z1_i) + kd_i (r_d,i' - z2_i) - z3_i,
//   kp_i = w_i^2, kd_i = 2 w_i   (closed loop (s + w_i)^2 once z3 = f),
// the contour loop stiff (w_c) and the tangential loop soft (w_m), as in the thesis's Lambda.
//
// Back to the axes. The task-space inertia is M_t = J^-T M J^-1 (2-47) and u = J^T u_force
// (u_force = J^-T u), so the force that produces the task acceleration u_t - J' q' is
// u = J^T M_t0 (u_t - J' q') = M0 J^-1 (u_t - J' q'). J^-1 with the nominal mass rather than
// plain J^T: M_t0 is not diagonal (the axes' masses differ 5.5 times and the tangent turns along
// the contour), so J^T alone would couple rc and rm and make the input gain of each coordinate
// vary along the contour; with M0 J^-1 both are constant and the ESO sees b0 = 1. J' q' is taken
// from the reference: r_d'' = J(q_d) q_d'' + J'(q_d) q_d' exactly, so
// J' q' ~ r_d'' - J q_d'' near the desired point, and the command becomes
//   u = M0 (q_d'' + J^-1 (u_t - r_d'')) + B0 q_hat' + A0 S_f(q_hat'),  q_hat' = J^-1 [z2_c, z2_m],
// the Cartesian feedforward of the reference acceleration plus task-space feedback; what the
// approximation misses (J(q) - J(q_d), a few micrometres of tracking error) is part of f.
//
// Bandwidths (h = 0.2 ms, linmotor): see GtcfAdrcGains. Delay: the ESO turns a late command into
// a disturbance and cancels it one observer time constant later, which adds phase lag to the
// loop. Linearised per coordinate (continuous, b = b0), the default loop crosses over at
// 822 rad/s with 41 deg phase margin: delay margin 0.88 ms (SARC's contour loop: 1.4 ms when x
// carries it, 3.3 ms when y does); in simulation it holds 0.8 ms and fails at 1 ms constant delay.
// Feeding the observers the command of d periods ago (observer_input_delay = d, d h = the loop
// delay) makes their model right again (a Smith-predictor-like observer input) and restores the
// margin up to 2 ms (`netmc sim --preset thesis-ellipse-delay`, docs/reproductions/thesis.md).

#include <array>
#include <deque>
#include <memory>

#include "control/contouring/contour_controller.hpp"
#include "control/axis/extended_state_observer.hpp"
#include "control/task_space/task_frame.hpp"

namespace netmc::control {

struct GtcfAdrcGains {
  // Cartesian nominal model, thesis ch. 2 (the same as SARC's).
  Eigen::Vector2d mass{0.1, 0.55};     // M0 [V/(m/s^2)]
  Eigen::Vector2d damping{0.4, 0.5};   // B0 [V/(m/s)]
  Eigen::Vector2d coulomb{0.1, 0.15};  // A0 [V]
  double friction_slope = 9000.0;      // S_f(v) = 2/pi atan(slope v)
  // Closed-loop bandwidths [rad/s] of (contour, tangential): SARC's contour loop (Lambda =
  // diag(100, 30), K_s = diag(100, 60)) has its poles at 100..1000 rad/s (contour) and
  // 30..600 rad/s (tangential), depending on which axis carries the coordinate; the
  // ESO cancels what SARC's adaptation and robust term handle, so the PD can sit at the top
  // of SARC's contour range with one double pole: w_c = 300, and w_m = 100 (soft tangential loop).
  Eigen::Vector2d loop_bandwidth{300.0, 100.0};
  // ESO bandwidths [rad/s]: 4-5x the loop (the usual ADRC rule, so that the estimate settles
  // before the loop reacts), and w_o h = 0.3 at h = 0.2 ms (forward-Euler poles 1 - w_o h = 0.7).
  Eigen::Vector2d observer_bandwidth{1500.0, 500.0};
  Discretization discretization = Discretization::forward_euler;
  // The observers' input is the task command of this many periods ago (0: this period's, as in
  // paper 001). Matching a known loop delay keeps it out of the disturbance estimate.
  unsigned observer_input_delay = 0;
};

class TaskSpaceAdrc final : public ContourController {
 public:
  TaskSpaceAdrc(const GtcfAdrcGains& gains, double sample_period_s,
                std::shared_ptr<const TaskFrame> frame);

  void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples) override;
  ContouringCycle step(std::size_t cycle, const ReferencePoint& reference,
                       const Eigen::Vector2d& measured) override;
  std::string describe() const override;

  // Observer of the contour (0) and tangential (1) coordinate.
  const ExtendedStateObserver& observer(int coordinate) const { return observers_[coordinate]; }
  // The observers' lumped disturbances, contour then tangential (task accelerations).
  std::vector<EstimateName> estimate_names() const override {
    return {{"fc_hat", "m/s^2"}, {"fm_hat", "m/s^2"}};
  }
  void read_estimates(double* out) const override {
    out[0] = observers_[0].disturbance();
    out[1] = observers_[1].disturbance();
  }

 private:
  GtcfAdrcGains gains_;
  std::shared_ptr<const TaskFrame> frame_;
  std::array<ExtendedStateObserver, 2> observers_;
  // rm unwrapped across the seam of a closed contour, so the tangential observer sees a
  // continuous coordinate.
  double rm_raw_ = 0.0;
  double rm_unwrapped_ = 0.0;
  std::deque<Eigen::Vector2d> recent_commands_;  // newest last, observer_input_delay + 1 long
};

}  // namespace netmc::control
