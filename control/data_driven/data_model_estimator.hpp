#pragma once
// Paper 002's data model of one axis, y(k+1) = y(k) + Phi(k) du(k) + Psi(k) dd(k) (eq. 9), with
// its three estimators run once per sample from the measured increment dy(k) (eq. 11-14):
//   kappa  = Psi^(k-1) dd^(k-1) + Phi^(k-1) du(k-1)                    (the predicted increment)
//   Phi^   += eta du(k-1) (dy(k) - kappa) / (mu + du(k-1)^2)          (eq. 12 = 14a)
//   Psi^   += tau dd^(k-1) (dy(k) - kappa) / (gamma + dd^(k-1)^2)     (eq. 13 = 14b)
//   dd^(k)  = dd^(k-1) + sigma Psi^(k-1) (dy(k) - kappa) / (rho + Psi^(k-1)^2)   (eq. 11 = 14c,
//             with sigma where 14c prints rho: digest 3.2 [G])
// and the resets of sec. 3.2: Phi^ back to its initial value when |Phi^| or |du| falls to
// epsilon, Psi^ likewise with |Psi^| or |dd^| (digest [A]: dd^ for the unmeasurable dd), and dd^
// back to 0 when |dd^| reaches 2 d0. Units are the controller's (paper 002: um and V).

#include <string>

namespace netmc::control {

struct DataModelEstimatorGains {
  double eta = 0.8, mu = 0.5;       // Phi^ step and penalty
  double tau = 0.8, gamma = 0.4;    // Psi^ step and penalty
  double sigma = 0.8, rho = 0.3;    // dd^ step and penalty
  double epsilon = 1e-5;            // reset threshold
  double phi_initial = 18.0;        // Phi^(1) (digest 3.7 [A]: T^2 Ka Kt rg / J = 18 um/V)
  double psi_initial = 18.0;        // Psi^(1)
  double disturbance_bound = 1.0;   // d0; dd^ resets at 2 d0
};

class DataModelEstimator {
 public:
  explicit DataModelEstimator(const DataModelEstimatorGains& gains);

  void reset();
  // Sample k: the measured increment dy(k) = y(k) - y(k-1) and the last control increment
  // du(k-1) = u(k-1) - u(k-2).
  void update(double output_increment, double previous_input_increment);

  double phi() const { return phi_; }                         // Phi^(k)
  double psi() const { return psi_; }                         // Psi^(k)
  double disturbance_increment() const { return increment_; } // dd^(k)
  // d^(k): the running sum of dd^ since the last reset (the disturbance estimate of sec. 6.1).
  double disturbance() const { return disturbance_; }
  const DataModelEstimatorGains& gains() const { return gains_; }
  std::string describe() const;

 private:
  DataModelEstimatorGains gains_;
  double phi_ = 0.0, psi_ = 0.0, increment_ = 0.0, disturbance_ = 0.0;
};

}  // namespace netmc::control
