#pragma once
// Desired-compensation indirect adaptive robust contouring control in task coordinates (thesis,
// paper 000, ch. 3, eq. 3-29..3-42), in a Cartesian form derived from them:
//   u = Phi_c theta_hat - d_hat_c - J^T K s,
// where the fast estimate d_hat_c of the low-frequency lumped disturbance follows (3-35),
// d_hat_c' = Proj(gamma_d J^-1 s) within |d_hat_c,i| <= d_c,max (J^-1 = J^T on the contour),
// and theta_hat comes from a least-squares estimator on the filtered model (3-38..3-42):
//   u_f = Upsilon_f^T theta, Upsilon_f^T = [x''_f 0 x'_f 0 S_f(x')_f 0 -1_f 0; 0 y''_f ...]
//   (d_n column -1 as eq. 3-2 implies; 3-39 prints +1), prediction error sigma = Upsilon_f^T theta_hat - u_f,
//   tau = -Upsilon_f sigma / (1 + nu tr(Upsilon_f^T Gamma Upsilon_f)),
//   Gamma' = kappa Gamma - Gamma Upsilon_f Upsilon_f^T Gamma / (1 + nu tr(...)) while
//   lambda_max of Gamma's 6x6 physical block <= rho_M (netmc's assumption [A]: the thesis's Gamma(0)
//   has 5000 > rho_M on the offsets), else 0; theta_hat' = Gamma tau, clamped into the box ([A]).
// H_f is second order (damping 0.7, cut-off per axis); x''_f is the derivative of the filtered
// velocity, so no second difference of positions is taken. Filters run by the trapezoidal rule;
// the command enters as the value held over the last period (zero-order hold).

#include <memory>
#include <vector>

#include "control/contouring/contour_controller.hpp"
#include "control/estimation/projected_least_squares.hpp"
#include "control/estimation/second_order_low_pass.hpp"
#include "control/task_space/task_space_darc.hpp"
#include "control/task_space/task_space_sliding_variable.hpp"

namespace netmc::control {

using CovarianceMatrix = Eigen::Matrix<double, 8, 8>;

// Thesis section 3.5, controller C2.
struct DiarcGains {
  ParameterVector initial_estimate = DarcGains{}.initial_estimate;
  ParameterVector lower = DarcGains{}.lower;
  ParameterVector upper = DarcGains{}.upper;
  ParameterVector initial_covariance = (ParameterVector() << 10, 10, 10, 10, 10, 10, 5000, 5000).finished();
  double forgetting = 0.1;        // kappa [1/s]
  double normalization = 0.1;     // upsilon
  double covariance_limit = 500;  // rho_M, on the physical 6x6 block
  Eigen::Vector2d filter_cutoff_hz{250.0, 150.0};
  double filter_damping = 0.7;
  Eigen::Vector2d disturbance_bound{1.0, 1.0};        // d_c,max [V]
  Eigen::Vector2d disturbance_adaptation{1e4, 1e4};   // gamma_d
  double friction_slope = 9000.0;
  Eigen::Vector2d lambda{100.0, 30.0};
  Eigen::Vector2d feedback{100.0, 60.0};  // K
};

class TaskSpaceDiarc final : public ContourController {
 public:
  TaskSpaceDiarc(const DiarcGains& gains, double sample_period_s, std::shared_ptr<const TaskFrame> frame,
                 const InitializationFilterSettings& filter = {},
                 LocalFrameRate local_rate = LocalFrameRate::frozen);

  void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples) override;
  ContouringCycle step(std::size_t cycle, const ReferencePoint& reference,
                       const Eigen::Vector2d& measured) override;
  std::string describe() const override;

  const ParameterVector& parameter_estimate() const { return estimator_.estimate(); }
  // theta_hat (8) then d_hat_c (2).
  std::vector<EstimateName> estimate_names() const override;
  void read_estimates(double* out) const override;
  const Eigen::Vector2d& disturbance_estimate() const { return disturbance_; }
  const CovarianceMatrix& covariance() const { return estimator_.covariance(); }

 private:
  void estimate_parameters(const Eigen::Vector2d& velocity);

  DiarcGains gains_;
  double h_;
  TaskSpaceSlidingVariable sliding_;
  ProjectedLeastSquares<8, 2, 6> estimator_;  // Gamma limited on the physical 6x6 block
  Eigen::Vector2d disturbance_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d last_command_ = Eigen::Vector2d::Zero();
  // Per axis: H_f of the velocity, of S_f(velocity), of 1 and of the command.
  std::vector<SecondOrderLowPass> velocity_filter_, friction_filter_, unit_filter_, command_filter_;
};

}  // namespace netmc::control
