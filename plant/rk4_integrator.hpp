#pragma once
// Classical fourth-order Runge-Kutta for a second-order axis x'' = accel(t, x, x'), used where a
// plant is nonlinear (friction, cogging) or its disturbance varies over the step. The step is cut
// into n = ceil(duration / max_substep) equal sub-steps (see substep_count). Header-only so the
// acceleration lambda inlines; no heap use.

namespace netmc::plant {

// Integrates (x, v) from t0 over `duration` in `substeps` equal RK4 sub-steps.
template <class Accel>
void rk4_second_order(double& x, double& v, double t0, double duration, long long substeps,
                      Accel&& accel) {
  const double h = duration / static_cast<double>(substeps);
  const double half = 0.5 * h;
  for (long long i = 0; i < substeps; ++i) {
    // Sub-step start from the index, not an accumulated sum, so t does not drift.
    const double t = t0 + static_cast<double>(i) * h;
    const double k1x = v;
    const double k1v = accel(t, x, v);
    const double k2x = v + half * k1v;
    const double k2v = accel(t + half, x + half * k1x, k2x);
    const double k3x = v + half * k2v;
    const double k3v = accel(t + half, x + half * k2x, k3x);
    const double k4x = v + h * k3v;
    const double k4v = accel(t + h, x + h * k3x, k4x);
    x += (h / 6.0) * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    v += (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  }
}

}  // namespace netmc::plant
