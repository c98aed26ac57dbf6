#pragma once
// Paper 002's data model of one axis, y(k+1) = y(k) + Phi(k) du(k) + Psi(k) dd(k) (eq. 9), with
// its three estimators run once per sample from the measured increment dy(k) (eq. 11-14):
//   kappa  = Psi^(k-1) dd^(k-1) + Phi^(k-1) du(k-1)                    (the predicted increment)
//   Phi^   += eta du(k-1) (dy(k) - kappa) / (mu + du(k-1)^2)          (eq. 12 = 14a)
//   Psi^   += tau dd^(k-1) (dy(k) - kappa) / (gamma + dd^(k-1)^2)     (eq. 13 = 14b)
//   dd^(k)  = dd^(k-1) + sigma Psi^(k-1) (dy(k) - kappa) / (rho + Psi^(k-1)^2)   (eq. 11 = 14c,
//             with sigma where 14c prints rho, read as a misprint)
// and the resets of section 3.3: Phi^ back to its initial value when |Phi^| or |du| falls to
// epsilon, Psi^ likewise with |Psi^| or |dd^| (netmc's assumption [A]: dd^ for the unmeasurable dd), and dd^
// back to 0 when |dd^| reaches 2 d0. Units are the controller's (paper 002: um and V).

#include <string>
#include <string_view>

namespace netmc::control {

// Which data model a data-driven law (mfa-dtsmc, mfac) identifies and inverts:
//   compact  paper 002's compact form, eq. 9: y(k+1) = y(k) + Phi du(k) (+ Psi dd(k));
//   full     a full-form (L_y = 2, d = 1) data model, not the paper's compact form:
//            dy(k+1) = a1 dy(k) + a2 dy(k-1) + b0 du(k-1) (+ Psi dd(k)), FullFormDataModel below.
enum class DataModelForm { compact, full };

const char* data_model_form_name(DataModelForm form);  // "compact" | "full"
// Throws std::invalid_argument naming `field` for anything but "compact" or "full".
DataModelForm parse_data_model_form(std::string_view name, std::string_view field);

struct DataModelEstimatorGains {
  double eta = 0.8, mu = 0.5;       // Phi^ step and penalty
  double tau = 0.8, gamma = 0.4;    // Psi^ step and penalty
  double sigma = 0.8, rho = 0.3;    // dd^ step and penalty
  double epsilon = 1e-5;            // reset threshold
  double phi_initial = 18.0;        // Phi^(1) (netmc's assumption [A]: T^2 Ka Kt rg / J = 18 um/V)
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
  // Only Psi^ and dd^ (eq. 14b, 14c and their resets) from a residual dy(k) - kappa computed by
  // another data model (the full form); Phi^ is left alone.
  void update_disturbance(double residual);

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

// A full-form (L_y = 2, d = 1) data model, not the paper's compact form (eq. 9):
//   dy(k+1) = a1 dy(k) + a2 dy(k-1) + b0 du(k-1) [+ Psi dd(k)]
// It holds paper 002's plant exactly: eq. 2, y(k+2) = 1.68125 y(k+1) - 0.68125 y(k) + 18 (u(k) + d(k)),
// is dy(k+2) = 1.68125 dy(k+1) - 0.68125 dy(k) + 18 (du(k) + dd(k)): u(k) first moves y(k+2), which
// the compact form cannot express (it gives u(k) to y(k+1)). (a1, a2, b0) are estimated by the
// normalised projection of eq. 12 with the paper's eta and mu, on the regressor of dy(k):
//   r(k)  = dy(k) - a1 dy(k-1) - a2 dy(k-2) - b0 du(k-2) - [Psi^ dd^](k-1)
//   theta += eta phi r / (mu + |phi|^2),  theta = (a1, a2, b0), phi = (dy(k-1), dy(k-2), du(k-2))
// with the compact form's reset of b0 (to b0(1) when |b0| or |du(k-2)| <= epsilon, or b0 changes
// sign). a starts at (2, -1), a pure double integrator. The law then aims at the free response
// y^(k+2 | du(k) = 0), on which du(k) acts with gain b0.
struct FullFormDataModelGains {
  double eta = 0.8, mu = 0.5, epsilon = 1e-5;
  double b0_initial = 18.0;                      // um/V, as Phi^(1)
  double a1_initial = 2.0, a2_initial = -1.0;    // the double integrator
};

// A law's full-form gains from its own (eta, mu, epsilon, phi_initial): the compact form's step,
// penalty, reset threshold and Phi^(1) carry over, b0 starting at Phi^(1).
template <class Gains>
FullFormDataModelGains full_form_gains(const Gains& g) {
  FullFormDataModelGains f;
  f.eta = g.eta;
  f.mu = g.mu;
  f.epsilon = g.epsilon;
  f.b0_initial = g.phi_initial;
  return f;
}

class FullFormDataModel {
 public:
  explicit FullFormDataModel(const FullFormDataModelGains& gains);

  void reset();
  // Sample k: the measured increment dy(k) and the disturbance part of the prediction
  // (Psi^ dd^ of k-1, 0 without one); returns the residual r(k) before the update.
  double update(double output_increment, double disturbance_part = 0.0);
  // Free response (du(k) = 0) from y(k): y^(k+1) and y^(k+2), with `disturbance_part` per step.
  void free_response(double position, double disturbance_part, double& next, double& after) const;
  // Sample k's input increment du(k), once chosen.
  void commit(double input_increment);

  double a1() const { return a1_; }
  double a2() const { return a2_; }
  double b0() const { return b0_; }
  const FullFormDataModelGains& gains() const { return gains_; }
  std::string describe() const;

 private:
  FullFormDataModelGains gains_;
  double a1_ = 0.0, a2_ = 0.0, b0_ = 0.0;
  double dy0_ = 0.0, dy1_ = 0.0, dy2_ = 0.0;  // dy(k), dy(k-1), dy(k-2)
  double du1_ = 0.0, du2_ = 0.0;              // du(k-1), du(k-2)
};

}  // namespace netmc::control
