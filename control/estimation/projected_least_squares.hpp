#pragma once
// The thesis's least-squares estimator with forgetting, covariance limit and box projection
// (paper 000, eq. 3-40..3-42 and 5-40/5-41), one explicit Euler step per sample, for P parameters
// and M outputs y_f = Phi_f theta (Phi_f: the M x P filtered regressor, rows F_f^T):
//   sigma = Phi_f theta_hat - y_f,  nu = 1 + upsilon tr(Phi_f Gamma Phi_f^T),
//   theta_hat' = Proj(-Gamma Phi_f^T sigma / nu),
//   Gamma' = alpha Gamma - Gamma Phi_f^T Phi_f Gamma / nu  while lambda_max(Gamma_LxL) <= rho_M, else 0,
// with Gamma_LxL its leading L x L block (chapter 3 limits only the physical block). Projection
// for a non-diagonal Gamma: clamp into the box after the step (digest 2.12 [A]).
// Fixed-size Eigen throughout: update() does not allocate. The caller validates the settings.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "control/task_space/box_projection.hpp"

namespace netmc::control {

template <int P, int M, int L = P>
class ProjectedLeastSquares {
 public:
  static_assert(L >= 1 && L <= P);
  using Vector = Eigen::Matrix<double, P, 1>;
  using Covariance = Eigen::Matrix<double, P, P>;
  using Regressor = Eigen::Matrix<double, M, P>;
  using Output = Eigen::Matrix<double, M, 1>;

  struct Settings {
    Vector initial_estimate = Vector::Zero();
    Vector lower = Vector::Constant(-1.0);
    Vector upper = Vector::Constant(1.0);
    Vector initial_covariance = Vector::Ones();  // Gamma(0), diagonal
    double forgetting = 0.0;                     // alpha (1/s)
    double normalization = 0.0;                  // upsilon
    double covariance_limit = 1.0;               // rho_M
  };

  explicit ProjectedLeastSquares(const Settings& settings) : settings_(settings) { reset(); }

  void reset() {
    estimate_ = settings_.initial_estimate;
    covariance_ = settings_.initial_covariance.asDiagonal();
  }

  void update(const Regressor& regressor, const Output& measurement, double h) {
    const Output prediction_error = regressor * estimate_ - measurement;
    const double normalizer =
        1.0 + settings_.normalization * (regressor * covariance_ * regressor.transpose()).trace();
    const Vector tau = -regressor.transpose() * prediction_error / normalizer;
    const Vector rate = covariance_ * tau;
    for (int i = 0; i < P; ++i) {
      estimate_[i] = projected_step(estimate_[i], rate[i], settings_.lower[i], settings_.upper[i], h);
    }
    if (within_limit()) {
      const Eigen::Matrix<double, P, M> gain = covariance_ * regressor.transpose();
      covariance_ += h * (settings_.forgetting * covariance_ - gain * gain.transpose() / normalizer);
      covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
    }
  }

  const Vector& estimate() const { return estimate_; }
  const Covariance& covariance() const { return covariance_; }
  const Settings& settings() const { return settings_; }

 private:
  // lambda_max of the limited block <= rho_M. Its largest absolute row sum bounds lambda_max
  // (Gershgorin), so the eigenvalues are only computed when that bound is above the limit.
  bool within_limit() const {
    const auto block = covariance_.template topLeftCorner<L, L>();
    if (block.cwiseAbs().rowwise().sum().maxCoeff() <= settings_.covariance_limit) return true;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, L, L>> solver(block, Eigen::EigenvaluesOnly);
    return solver.eigenvalues().maxCoeff() <= settings_.covariance_limit;
  }

  Settings settings_;
  Vector estimate_;
  Covariance covariance_;
};

}  // namespace netmc::control
