#include "control/frequency/qft_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace netmc::control {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// ω^2 / (s^2 + 2 z ω s + ω^2): unit DC gain.
TransferFunction second_order_low_pass(double omega_rad_s, double damping) {
  return {{omega_rad_s * omega_rad_s}, {1.0, 2.0 * damping * omega_rad_s, omega_rad_s * omega_rad_s}};
}

// P/(1 + G P) of one axis at jω, from the values: no high-degree polynomial to round.
std::complex<double> closed_axis(const TransferFunction& plant, const TransferFunction& feedback_law,
                                 double omega_rad_s) {
  const std::complex<double> p = plant.at(omega_rad_s);
  return p / (1.0 + feedback_law.at(omega_rad_s) * p);
}

}  // namespace

StageAxisModel paper004_x_axis() {
  return {24.0, {{0.013, 0.040, 150.0}, {0.0023, 0.018, 292.0}, {0.0018, 0.027, 510.0}}, 50.0, 3.0};
}

StageAxisModel paper004_y_axis() {
  return {30.0, {{0.018, 0.0432, 182.0}, {0.0021, 0.0531, 302.0}}, 50.0, 3.0};
}

TransferFunction stage_axis_plant(const StageAxisModel& axis) {
  if (!(axis.mass_kg > 0.0)) throw std::invalid_argument("stage axis: the mass must be positive");
  TransferFunction plant({1.0}, {axis.mass_kg, 0.0, 0.0});  // paper 004, eq. 1: rigid body
  for (const StageResonance& r : axis.resonances) {
    const double omega = kTwoPi * r.frequency_hz;
    plant = plant + TransferFunction({r.gain}, {1.0, 2.0 * r.damping_ratio * omega, omega * omega});
  }
  return plant;
}

TransferFunction stage_axis_feedback(const StageAxisModel& axis, double low_pass_damping) {
  if (!(axis.bandwidth_hz > 0.0) || !(axis.alpha > 0.0) || !(low_pass_damping > 0.0)) {
    throw std::invalid_argument("stage axis feedback: f_bw, alpha and z_lp must be positive");
  }
  // paper 004, eq. 2: corners spaced by α around the bandwidth.
  const double integral_hz = axis.bandwidth_hz / (axis.alpha * axis.alpha);
  const double derivative_hz = axis.bandwidth_hz / axis.alpha;
  const double low_pass_hz = axis.alpha * axis.bandwidth_hz;
  const double kp = axis.mass_kg * std::pow(kTwoPi * axis.bandwidth_hz, 2) / axis.alpha;
  const TransferFunction integral({1.0, kTwoPi * integral_hz}, {1.0, 0.0});
  const TransferFunction lead({1.0 / (kTwoPi * derivative_hz), 1.0}, {1.0});
  return TransferFunction::gain(kp) * integral * lead * second_order_low_pass(kTwoPi * low_pass_hz, low_pass_damping);
}

CrossCouplingLoop paper004_cross_coupling_loop(double feedback_low_pass_damping) {
  const StageAxisModel x = paper004_x_axis(), y = paper004_y_axis();
  return {stage_axis_plant(x), stage_axis_feedback(x, feedback_low_pass_damping), stage_axis_plant(y),
          stage_axis_feedback(y, feedback_low_pass_damping)};
}

std::complex<double> equivalent_plant(const CrossCouplingLoop& loop, double cx_squared, double omega_rad_s) {
  // paper 004, eq. 14
  return cx_squared * closed_axis(loop.x_plant, loop.x_feedback, omega_rad_s) +
         (1.0 - cx_squared) * closed_axis(loop.y_plant, loop.y_feedback, omega_rad_s);
}

std::complex<double> contour_open_loop(const TransferFunction& cross_coupling, const CrossCouplingLoop& loop,
                                       double cx_squared, double omega_rad_s) {
  return cross_coupling.at(omega_rad_s) * equivalent_plant(loop, cx_squared, omega_rad_s);
}

std::vector<double> qft_template_cx_squared() {
  std::vector<double> cx_squared;
  for (int i = 0; i <= 20; ++i) cx_squared.push_back(std::pow(std::sin(0.025 * std::numbers::pi * i), 2));
  return cx_squared;
}

std::vector<double> qft_design_frequencies_hz() { return {0.1, 0.5, 1.0, 10.0, 35.0, 100.0, 1000.0}; }

TransferFunction qft_tracking_bound() { return {{806.0, 403225.0}, {1.0, 851.0, 403225.0}}; }  // eq. 18

std::vector<QftBoundCheck> check_qft_bounds(const TransferFunction& cross_coupling, const CrossCouplingLoop& loop,
                                            const std::vector<double>& frequencies_hz) {
  const TransferFunction tracking = qft_tracking_bound();
  const std::vector<double> template_points = qft_template_cx_squared();
  std::vector<QftBoundCheck> checks;
  for (const double f : frequencies_hz) {
    if (!(f > 0.0) || !std::isfinite(f)) throw std::invalid_argument("QFT bounds: frequencies must be positive and finite");
    const double omega = kTwoPi * f;
    // K is linear in C_x^2: the two closed axes once per frequency, then the template.
    const std::complex<double> c = cross_coupling.at(omega);
    const std::complex<double> kx = closed_axis(loop.x_plant, loop.x_feedback, omega);
    const std::complex<double> ky = closed_axis(loop.y_plant, loop.y_feedback, omega);
    QftBoundCheck check;
    check.frequency_hz = f;
    check.tracking_bound = std::abs(tracking.at(omega));
    for (const double cx2 : template_points) {
      const std::complex<double> open_loop = c * (cx2 * kx + (1.0 - cx2) * ky);
      check.max_sensitivity = std::max(check.max_sensitivity, std::abs(1.0 / (1.0 + open_loop)));          // eq. 16
      check.max_complementary = std::max(check.max_complementary, std::abs(open_loop / (1.0 + open_loop)));  // eq. 17
    }
    check.max_tracking_ratio = check.max_complementary / check.tracking_bound;
    checks.push_back(check);
  }
  return checks;
}

TransferFunction paper004_eq19_cross_coupling() { return TransferFunction::gain(2.2e9) * TransferFunction::integrator(); }

TransferFunction paper004_eq20_cross_coupling() {
  const TransferFunction zero_pair({1.0, 2.0 * 374.4, 374.4 * 374.4}, {1.0});
  const TransferFunction pole_pair({1.0}, {1.0, 2.0 * 11230.0, 11230.0 * 11230.0});
  return TransferFunction::gain(2.75e11) * zero_pair * TransferFunction::integrator() * pole_pair;
}

TransferFunction paper004_pid_cross_coupling(const FilteredPidCrossCouplingGains& gains) {
  const TransferFunction pid({gains.kd, gains.kp, gains.ki}, {1.0, 0.0});
  return pid * second_order_low_pass(kTwoPi * gains.low_pass_hz, gains.low_pass_damping);  // eq. 13
}

}  // namespace netmc::control
