#pragma once
// DARC with cogging-force compensation in task coordinates (thesis, paper 000, ch. 4, eq. 4-3 to
// 4-20): the model of ch. 3 plus the cogging force of each axis, periodic in its position with the
// magnet pitch P (eq. 4-2, harmonics of eq. 4-23: X 1, 2, 3 and Y 1, 6, 12),
//   M q'' + B q' + A S_f + F_r(q) = u + d_N,  F_rx = sum_i S_xi sin(2 pi i x/P) + C_xi cos(2 pi i x/P),
// so theta_r = [M1, M2, B1, B2, A1, A2, S_x1, C_x1, ..., S_y12, C_y12, d_N1, d_N2] (8 + 4m = 20
// entries) and the Cartesian regressor of ch. 3 gains +sin, +cos columns per harmonic (derived
// from eq. 4-2). u = Phi_r theta_hat - J^T K s, tau = -Phi_r^T J^-1 s, theta_hat' = Proj(Gamma tau). The
// friction regressor uses the desired velocity, S_f(q_d') (ch. 4's C1 and C2). With the cogging
// rows of Gamma at 0 this is ch. 4's C1 (no compensation), at 500 its C2.

#include <array>
#include <memory>
#include <vector>

#include "control/contouring/contour_controller.hpp"
#include "control/task_space/task_space_sliding_variable.hpp"

namespace netmc::control {

inline constexpr int kCoggingHarmonicsPerAxis = 3;
inline constexpr int kCoggingParameters = 8 + 4 * kCoggingHarmonicsPerAxis;  // 20
using CoggingParameterVector = Eigen::Matrix<double, kCoggingParameters, 1>;

// Thesis section 4.4, controller C2: bounds, Gamma, theta_hat(0), harmonics.
struct CoggingDarcGains {
  CoggingParameterVector initial_estimate = (CoggingParameterVector() << 0.12, 0.5, 0.3, 0.4, 0.1, 0.15,
                                             0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0).finished();
  CoggingParameterVector lower = (CoggingParameterVector() << 0.06, 0.4, 0.3, 0.3, 0.05, 0.08, -0.2, -0.2, -0.2,
                                  -0.2, -0.2, -0.2, -0.2, -0.2, -0.2, -0.2, -0.2, -0.2, -1, -0.5).finished();
  CoggingParameterVector upper = (CoggingParameterVector() << 0.25, 0.6, 0.6, 0.6, 0.15, 0.25, 0.2, 0.2, 0.2, 0.2,
                                  0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 1, 0.5).finished();
  CoggingParameterVector adaptation = (CoggingParameterVector() << 10, 10, 10, 10, 10, 10, 500, 500, 500, 500, 500,
                                       500, 500, 500, 500, 500, 500, 500, 1e4, 1e4).finished();
  double pitch_m = 0.05;                                     // P (eq. 4-23)
  std::array<int, kCoggingHarmonicsPerAxis> x_harmonics{1, 2, 3};
  std::array<int, kCoggingHarmonicsPerAxis> y_harmonics{1, 6, 12};
  double friction_slope = 9000.0;         // S_f(v) = 2/pi atan(slope v)
  Eigen::Vector2d lambda{100.0, 30.0};    // Lambda = diag(contour, tangential)
  Eigen::Vector2d feedback{100.0, 60.0};  // K_s
};

// The Cartesian regressor Phi_r (2 x 20) at the equivalent acceleration, the measured velocity,
// the desired velocity (friction) and the measured position (cogging).
Eigen::Matrix<double, 2, kCoggingParameters> cogging_darc_regressor(const CoggingDarcGains& gains,
                                                                    const Eigen::Vector2d& equivalent_acceleration,
                                                                    const Eigen::Vector2d& velocity,
                                                                    const Eigen::Vector2d& desired_velocity,
                                                                    const Eigen::Vector2d& position);

class TaskSpaceCoggingDarc final : public ContourController {
 public:
  // Global frame: `frame` of the contour. Local frame: frame == nullptr. Throws
  // std::invalid_argument naming the gain when one is invalid.
  TaskSpaceCoggingDarc(const CoggingDarcGains& gains, double sample_period_s, std::shared_ptr<const TaskFrame> frame,
                       const InitializationFilterSettings& filter = {},
                       LocalFrameRate local_rate = LocalFrameRate::frozen);

  void begin_iteration(const Eigen::Vector2d& initial_position, std::size_t samples) override;
  ContouringCycle step(std::size_t cycle, const ReferencePoint& reference, const Eigen::Vector2d& measured) override;
  std::string describe() const override;
  std::vector<EstimateName> estimate_names() const override;
  void read_estimates(double* out) const override;

  const CoggingParameterVector& parameter_estimate() const { return estimate_; }

 private:
  CoggingDarcGains gains_;
  double h_;
  TaskSpaceSlidingVariable sliding_;
  CoggingParameterVector estimate_;
};

}  // namespace netmc::control
