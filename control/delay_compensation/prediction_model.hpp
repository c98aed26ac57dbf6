#pragma once
// The model a delay compensator runs forward over the measured delay (Smith; Yi, An and Choi's
// step-ahead predictor): one axis as x'' = a x' + b u - c tanh(x' / v_s) + d, with d the lumped
// disturbance, held over the prediction. A plant's nominal model gives a, b, c (paper 001, eq. 3
// for seed001); ADRC's own is a = 0, b = b0, c = 0 (paper 001, eq. 9: its ESO sees everything but
// b0 u as disturbance).

#include <algorithm>
#include <cmath>

namespace netmc::control {

struct PredictionModel {
  double damping_per_s = 0.0;            // a (1/s), <= 0 for a damped axis
  double input_gain = 1.0;               // b ((m/s^2) per input unit)
  double coulomb_m_s2 = 0.0;             // c (m/s^2), Coulomb friction's level
  double coulomb_velocity_scale_m_s = 1e-3;  // v_s (m/s), the tanh's width
  double observer_bandwidth_rad_s = 100.0;  // poles of the delayed-time observer
};

// Position, velocity and lumped disturbance of one axis.
struct PredictedState {
  double position_m = 0.0;
  double velocity_m_s = 0.0;
  double disturbance_m_s2 = 0.0;
};

// The model over `duration_s` with `input` held: exact for the linear model (no discretization
// error, so a prediction over several arrivals of commands is as good as the model); RK4 in steps
// of at most 1 ms with friction (its stiffest slope, c / v_s = 85 1/s for seed001's Y, gives
// |lambda h| = 0.085, as the plant's own sub-steps).
inline void advance_model(const PredictionModel& model, PredictedState& state, double duration_s, double input) {
  if (!(duration_s > 0.0)) return;
  if (model.coulomb_m_s2 != 0.0) {
    const auto acceleration = [&](double velocity) {
      return model.damping_per_s * velocity + model.input_gain * input + state.disturbance_m_s2 -
             model.coulomb_m_s2 * std::tanh(velocity / model.coulomb_velocity_scale_m_s);
    };
    const int steps = std::max(1, static_cast<int>(std::ceil(duration_s / 1e-3)));
    const double dt = duration_s / steps;
    for (int i = 0; i < steps; ++i) {
      const double v = state.velocity_m_s;
      const double k1 = acceleration(v), k2 = acceleration(v + 0.5 * dt * k1), k3 = acceleration(v + 0.5 * dt * k2),
                   k4 = acceleration(v + dt * k3);
      state.position_m += dt * (v + dt / 6.0 * (k1 + k2 + k3));
      state.velocity_m_s += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    return;
  }
  const double a = model.damping_per_s;
  const double acceleration = model.input_gain * input + state.disturbance_m_s2;
  if (std::abs(a * duration_s) < 1e-6) {
    state.position_m += state.velocity_m_s * duration_s + 0.5 * acceleration * duration_s * duration_s;
    state.velocity_m_s += acceleration * duration_s;
    return;
  }
  const double growth = std::exp(a * duration_s);
  const double integral = (growth - 1.0) / a;  // the integral of exp(a s) over the duration
  state.position_m += state.velocity_m_s * integral + acceleration * (integral - duration_s) / a;
  state.velocity_m_s = state.velocity_m_s * growth + acceleration * integral;
}

}  // namespace netmc::control
