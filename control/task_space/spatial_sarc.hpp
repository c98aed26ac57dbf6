#pragma once
// Simple adaptive robust contouring control of three axes in the n-dimensional global task frame
// (thesis, paper 000, ch. 6, eq. 6-8..6-24, with the ch. 2 SARC law 2-50..2-60 in place of the
// full ARC): e = r(q) - r_d with r = [rc1, rc2, rm] of a SpatialCircle and r_d = [0, 0, rm(q_d)],
// s = J q' - r_d' + Lambda e, u = M q_eq'' + B q' + A S_f(q') + F_l_hat - J^T K_s s, and
// F_l_hat' = Proj(-Gamma J^{-1} s) into |F_l,i| <= F_M,i. Velocity is differenced from the
// measured positions (second-order backward difference, as TaskSpaceSarc does).

#include <Eigen/Dense>
#include <memory>

#include "control/trajectory/spatial_circle.hpp"

namespace netmc::control {

struct SpatialSarcGains {
  // Per axis: the thesis's X and Y nominals (ch. 2), and Y's again for the third axis (the
  // plant catalog's third axis copies Y).
  Eigen::Vector3d mass{0.1, 0.55, 0.55};       // M [V/(m/s^2)]
  Eigen::Vector3d damping{0.4, 0.5, 0.5};      // B [V/(m/s)]
  Eigen::Vector3d coulomb{0.1, 0.15, 0.15};    // A [V]
  double friction_slope = 9000.0;              // S_f(v) = 2/pi atan(slope v)
  // Per task coordinate [rc1, rc2, rm]: both contour coordinates get the thesis's contour gains.
  Eigen::Vector3d lambda{100.0, 100.0, 30.0};
  Eigen::Vector3d feedback{100.0, 100.0, 60.0};  // K_s
  // Per axis.
  Eigen::Vector3d adaptation{1e4, 1e4, 1e4};         // Gamma
  Eigen::Vector3d uncertainty_bound{1.5, 1.5, 1.5};  // F_M [V]
};

class SpatialSarc {
 public:
  // Throws std::invalid_argument for a non-positive period, mass, lambda or bound, or a
  // negative damping, coulomb, feedback or adaptation gain.
  SpatialSarc(const SpatialSarcGains& gains, double sample_period_s,
              std::shared_ptr<const SpatialCircle> contour);

  // Start with the axes at rest at `initial_position`.
  void begin(const Eigen::Vector3d& initial_position);
  // One sample: the desired point and the measured positions in, the axis commands [V] out.
  Eigen::Vector3d step(const SpatialReferencePoint& reference, const Eigen::Vector3d& measured);

  // The task error e = r(q) - r_d of the last step: [rc1, rc2, rm - rm_d].
  const Eigen::Vector3d& task_error() const { return error_; }
  const Eigen::Vector3d& uncertainty_estimate() const { return estimate_; }

 private:
  SpatialSarcGains gains_;
  double h_;
  std::shared_ptr<const SpatialCircle> contour_;
  Eigen::Vector3d previous_position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d earlier_position_ = Eigen::Vector3d::Zero();
  int samples_seen_ = 0;
  Eigen::Vector3d previous_equivalent_velocity_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d estimate_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d error_ = Eigen::Vector3d::Zero();
};

}  // namespace netmc::control
