#pragma once
// Paper 004's single-axis loop (section 1): the PID-type feedback G_c of eq. 2, spaced by α
// around the bandwidth f_bw, plus the acceleration feedforward G_f(s) = 0.85 m s^2, i.e.
//   u = G_c(z) E + 0.85 m r'',   E = r - y,
// with G_c discretised by Tustin at the loop rate. Force in N, lengths in m.

#include <string>

#include "control/frequency/transfer_function.hpp"
#include "control/frequency/tustin.hpp"

namespace netmc::control {

// Defaults: paper 004, Table 1 (X axis); the Y axis has m = 30 kg (Table 2).
struct FeedforwardPidGains {
  double mass_kg = 24.0;               // m: sets K_p = m (2π f_bw)^2/α and the feedforward
  double bandwidth_hz = 50.0;          // f_bw
  double alpha = 3.0;                  // α: f_i = f_bw/α^2, f_d = f_bw/α, f_lp = α f_bw
  double low_pass_damping = 0.7;       // z_lp of eq. 2 (not in the paper: netmc's assumption [A])
  double feedforward_fraction = 0.85;  // of m r'' (paper 004, section 1: 85 % of the mass)
};

FeedforwardPidGains paper004_x_axis_gains();  // Table 1
FeedforwardPidGains paper004_y_axis_gains();  // Table 2

// G_c(s) of eq. 2 for these gains (the frequency library's stage_axis_feedback).
TransferFunction feedforward_pid_feedback(const FeedforwardPidGains& gains);

class FeedforwardPidAxis {
 public:
  // Throws std::invalid_argument naming the gain for a non-positive mass, bandwidth, α or z_lp,
  // a non-finite feedforward fraction, or a low-pass corner α f_bw at or above the Nyquist
  // frequency 1/(2T).
  FeedforwardPidAxis(const FeedforwardPidGains& gains, double sample_period_s);

  // Back to rest: the feedback filter's state is zero.
  void reset();
  // u(k) = G_c(z) E(k) + u_ff(k); advances the feedback filter by one sample (no allocation).
  double step(double reference_position, double reference_acceleration, double measured_position);
  // u_ff = fraction m r'' (exact, no filtering).
  double feedforward(double reference_acceleration) const {
    return gains_.feedforward_fraction * gains_.mass_kg * reference_acceleration;
  }

  const FeedforwardPidGains& gains() const { return gains_; }
  const TransferFunction& continuous_feedback() const { return continuous_; }
  const DiscreteTransferFunction& discrete_feedback() const { return discrete_; }
  std::string describe() const;

 private:
  FeedforwardPidGains gains_;
  TransferFunction continuous_;
  DiscreteTransferFunction discrete_;
  DiscreteFilter feedback_;
};

}  // namespace netmc::control
