#pragma once
// Paper 004's QFT design of a cross-coupled contour controller C(s) (sections 1-3): the
// contour loop sees the two closed axis loops as one uncertain plant K(s) (eq. 14) whose
// uncertainty is C_x^2 = sin^2 φ, φ the path's tangent angle. For a given C(s) this checks, per
// design frequency and over the whole template, the sensitivity bound (eq. 16) and the tracking
// bound |T| <= |T_u| (eqs. 17, 18). SI units: s, rad/s, kg, N/m; frequencies named _hz are Hz.

#include <complex>
#include <vector>

#include "control/frequency/transfer_function.hpp"

namespace netmc::control {

// One resonance of eq. 1: K_i / (s^2 + 4π x_i f_i s + (2π f_i)^2).
struct StageResonance {
  double gain = 0.0;          // K_i, m/(N s^2)
  double damping_ratio = 0.0; // x_i
  double frequency_hz = 0.0;  // f_i
};

// One axis of the H-bridge stage and its feedback design targets (Tables 1 and 2).
struct StageAxisModel {
  double mass_kg = 0.0;                   // m
  std::vector<StageResonance> resonances;
  double bandwidth_hz = 0.0;              // f_bw
  double alpha = 0.0;                     // α: spacing of the corners around f_bw
};

StageAxisModel paper004_x_axis();  // Table 1
StageAxisModel paper004_y_axis();  // Table 2

// paper 004, eq. 1: P(s) = 1/(m s^2) + Σ K_i/(s^2 + 4π x_i f_i s + (2π f_i)^2), force to position.
TransferFunction stage_axis_plant(const StageAxisModel& axis);

// paper 004, eq. 2: G_c(s) = K_p ((s + 2π f_i)/s) (s/(2π f_d) + 1) ω_lp^2/(s^2 + 2 z_lp ω_lp s + ω_lp^2)
// with f_i = f_bw/α^2, f_d = f_bw/α, ω_lp = 2π α f_bw, K_p = m (2π f_bw)^2/α. The paper gives no
// z_lp for this filter; netmc assumes 0.7 [A].
TransferFunction stage_axis_feedback(const StageAxisModel& axis, double low_pass_damping = 0.7);

// Both axes, each with its plant and feedback: what the contour loop acts on.
struct CrossCouplingLoop {
  TransferFunction x_plant, x_feedback, y_plant, y_feedback;
};
CrossCouplingLoop paper004_cross_coupling_loop(double feedback_low_pass_damping = 0.7);

// paper 004, eq. 14: K(jω) = C_x^2 P_x/(1 + G_cx P_x) + (1 - C_x^2) P_y/(1 + G_cy P_y).
std::complex<double> equivalent_plant(const CrossCouplingLoop& loop, double cx_squared, double omega_rad_s);

// The open contour loop C(jω) K(jω) at one template point.
std::complex<double> contour_open_loop(const TransferFunction& cross_coupling, const CrossCouplingLoop& loop,
                                       double cx_squared, double omega_rad_s);

// The template: φ = 0 : 0.025π : 0.5π (21 points), C_x = sin φ; returns C_x^2.
std::vector<double> qft_template_cx_squared();
// {0.1, 0.5, 1, 10, 35, 100, 1000} Hz
std::vector<double> qft_design_frequencies_hz();

// paper 004, eq. 16: |S(jω)| <= 0.4, checked at the low design frequencies (f <= 10 Hz).
inline constexpr double kQftSensitivityBound = 0.4;
inline constexpr double kQftSensitivityBoundMaxFrequencyHz = 10.0;

// paper 004, eq. 18: T_u(s) = (806 s + 403 225)/(s^2 + 851 s + 403 225), the tracking bound of
// eq. 17 (overshoot 1.06, rise time <= 0.05 s, a zero at 500 rad/s).
TransferFunction qft_tracking_bound();

// One design frequency, worst case over the template.
struct QftBoundCheck {
  double frequency_hz = 0.0;
  double max_sensitivity = 0.0;     // max |S| = |1/(1 + CK)|, eq. 16
  double max_complementary = 0.0;   // max |T| = |CK/(1 + CK)|, eq. 17
  double tracking_bound = 0.0;      // |T_u(jω)|, eq. 18
  double max_tracking_ratio = 0.0;  // max |T| / |T_u|: at most 1 meets eq. 17
};

std::vector<QftBoundCheck> check_qft_bounds(const TransferFunction& cross_coupling,
                                            const CrossCouplingLoop& loop = paper004_cross_coupling_loop(),
                                            const std::vector<double>& frequencies_hz = qft_design_frequencies_hz());

// paper 004, eq. 19: the first try, C(s) = 2.2e9/s (violates eq. 17 at 35 Hz).
TransferFunction paper004_eq19_cross_coupling();
// paper 004, eq. 20: the final QFT design, C(s) = 2.75e11 (s + 374.4)^2 / (s (s + 11 230)^2).
TransferFunction paper004_eq20_cross_coupling();

// paper 004, Table 3: gains of the PID-type cross-coupling controller of eq. 13.
struct FilteredPidCrossCouplingGains {
  double kp = 5e5;
  double ki = 1e8;
  double kd = 3.0;
  double low_pass_hz = 100.0;      // the table's "ω_lp = 100 Hz", used as f_lp
  double low_pass_damping = 0.707; // z_lp
};
// paper 004, eq. 13: C(s) = (K_d s^2 + K_p s + K_i)/s · (2π f_lp)^2/(s^2 + 4π z_lp f_lp s + (2π f_lp)^2).
TransferFunction paper004_pid_cross_coupling(const FilteredPidCrossCouplingGains& gains = {});

}  // namespace netmc::control
