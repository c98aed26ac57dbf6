#pragma once
// Direct adaptive robust contouring control in task coordinates (thesis, paper 000, ch. 3,
// eq. 3-11..3-23), in a Cartesian form derived from them: with the regressor
//   Phi_c = [ q_eq1''  0  x'  0  S_f(x')  0  -1   0 ]
//           [ 0  q_eq2''  0  y'  0  S_f(y')  0  -1 ]
// and theta = [M1, M2, B1, B2, A1, A2, dn1, dn2] (model 3-2: M q'' + B q' + A S_f(q') = u + d_n),
//   u = Phi_c theta_hat - J^T K s,   tau = -Phi_c^T J^-1 s,   theta_hat' = Proj(Gamma tau),
// with the discontinuous projection (3-12) that keeps every element of theta_hat inside
// [theta_min, theta_max]. Same s, J and q_eq'' as SARC (TaskSpaceSlidingVariable), so in the
// global or the local task frame and with the initialization filter (eq. 2-67) in the global one.

#include <memory>
#include <vector>
#include <string>

#include "control/contouring/contour_controller.hpp"
#include "control/task_space/task_space_sliding_variable.hpp"

namespace netmc::control {

using ParameterVector = Eigen::Matrix<double, 8, 1>;

// Names and units of theta = [M1, M2, B1, B2, A1, A2, dn1, dn2] (model 3-2, volts), as estimates.
std::vector<EstimateName> parameter_estimate_names();

// Thesis section 3.5, controller C1: bounds (3-47), Gamma, theta_hat(0).
struct DarcGains {
  ParameterVector initial_estimate = (ParameterVector() << 0.1, 0.55, 0.3, 0.3, 0.1, 0.15, 0.0, 0.0).finished();
  ParameterVector lower = (ParameterVector() << 0.06, 0.4, 0.2, 0.3, 0.05, 0.08, -0.5, -0.5).finished();
  ParameterVector upper = (ParameterVector() << 0.25, 0.7, 0.6, 0.6, 0.15, 0.25, 0.5, 0.5).finished();
  ParameterVector adaptation = (ParameterVector() << 10, 10, 10, 10, 10, 10, 1e4, 1e4).finished();
  double friction_slope = 9000.0;         // S_f(v) = 2/pi atan(slope v)
  Eigen::Vector2d lambda{100.0, 30.0};    // Lambda = diag(contour, tangential)
  Eigen::Vector2d feedback{100.0, 60.0};  // K (total u_s gain)
};

// The regressor Phi_c of the Cartesian form (derived from eq. 3-17/3-18).
Eigen::Matrix<double, 2, 8> darc_regressor(const Eigen::Vector2d& equivalent_acceleration,
                                           const Eigen::Vector2d& velocity, double friction_slope);

// Throws std::invalid_argument("CONTROLLER theta...") unless theta_min <= theta_hat(0) <= theta_max,
// all finite, with positive lower bounds on the masses.
void require_parameter_box(const ParameterVector& initial, const ParameterVector& lower,
                           const ParameterVector& upper, const std::string& controller);

class TaskSpaceDarc final : public ContourController {
 public:
  // Global frame: `frame` of the contour. Local frame: frame == nullptr. Throws
  // std::invalid_argument naming the gain when one is invalid (theta_hat(0) outside the box).
  TaskSpaceDarc(const DarcGains& gains, double sample_period_s, std::shared_ptr<const TaskFrame> frame,
                const InitializationFilterSettings& filter = {},
                LocalFrameRate local_rate = LocalFrameRate::frozen);

  void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples) override;
  ContouringCycle step(std::size_t cycle, const ReferencePoint& reference,
                       const Eigen::Vector2d& measured) override;
  std::string describe() const override;

  const ParameterVector& parameter_estimate() const { return estimate_; }
  std::vector<EstimateName> estimate_names() const override;
  void read_estimates(double* out) const override;

 private:
  DarcGains gains_;
  double h_;
  TaskSpaceSlidingVariable sliding_;
  ParameterVector estimate_;
};

}  // namespace netmc::control
