#pragma once
// The thesis's least-squares estimator with forgetting, covariance limit and box projection
// (paper 000, eq. 3-40..3-42 and 5-40/5-41), one explicit Euler step per sample, for P parameters
// and M outputs y_f = Phi_f theta (Phi_f: the M x P filtered regressor, rows F_f^T):
//   sigma = Phi_f theta_hat - y_f,  nu = 1 + upsilon tr(Phi_f Gamma Phi_f^T),
//   theta_hat' = Proj(-Gamma Phi_f^T sigma / nu),
//   Gamma' = alpha Gamma - Gamma Phi_f^T Phi_f Gamma / nu  while lambda_max(Gamma_LxL) <= rho_M, else 0,
// with Gamma_LxL its leading L x L block (chapter 3 limits only the physical block). Projection
// for a non-diagonal Gamma: clamp into the box after the step (netmc's assumption [A]).
// Fixed-size Eigen throughout: update() does not allocate. The caller validates the settings.

#include <Eigen/Core>
#include <cmath>
#include <Eigen/Eigenvalues>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "control/estimation/box_projection.hpp"

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

// The estimator's settings from an adaptive law's gains, which name them as the thesis does:
// initial_estimate, lower, upper, initial_covariance (its diagonal, or one value for all),
// forgetting, normalization, covariance_limit.
template <class Estimator, class Gains>
typename Estimator::Settings least_squares_settings(const Gains& gains) {
  typename Estimator::Settings out;
  out.initial_estimate = gains.initial_estimate;
  out.lower = gains.lower;
  out.upper = gains.upper;
  if constexpr (std::is_arithmetic_v<std::decay_t<decltype(gains.initial_covariance)>>) {
    out.initial_covariance.setConstant(gains.initial_covariance);
  } else {
    out.initial_covariance = gains.initial_covariance;
  }
  out.forgetting = gains.forgetting;
  out.normalization = gains.normalization;
  out.covariance_limit = gains.covariance_limit;
  return out;
}

// theta_hat(0) within a finite box (the projection's precondition, thesis 3-29 / 5-16); throws
// std::invalid_argument naming `prefix`.lower, .upper or .initial_estimate.
template <class Vector>
void require_initial_estimate_in_box(const Vector& initial, const Vector& lower, const Vector& upper,
                                     const std::string& prefix) {
  for (Eigen::Index i = 0; i < initial.size(); ++i) {
    std::ostringstream text;
    if (!std::isfinite(lower[i]) || !std::isfinite(upper[i])) {
      text << prefix << (std::isfinite(lower[i]) ? ".upper" : ".lower") << ": expected finite bounds, entry " << i;
    } else if (!(lower[i] <= initial[i] && initial[i] <= upper[i])) {
      text << prefix << ".initial_estimate: expected lower <= initial <= upper, entry " << i << " is " << initial[i]
           << " outside [" << lower[i] << ", " << upper[i] << "]";
    } else {
      continue;
    }
    throw std::invalid_argument(text.str());
  }
}

}  // namespace netmc::control
