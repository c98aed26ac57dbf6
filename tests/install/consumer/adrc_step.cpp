// One axis under netmc::control's ADRC, outside netmc: a double integrator x'' = u + d with a
// constant load d the controller is not told of, asked to hold 1 mm. The observer's estimate of
// the load cancels it, so the axis settles on the reference: a PD loop with the same gains would
// stay d / kp = 1.25 mm short. Exits 1 if it does not settle.
#include <netmc/control/axis/adrc_controller.hpp>

#include <cmath>
#include <cstdio>

int main() {
  netmc::control::AdrcGains gains;
  gains.td_speed_factor = 160.0;
  gains.observer_bandwidth = 100.0;
  gains.input_gain = 1.0;
  gains.kp = 400.0;
  gains.kd = 40.0;
  const double h = 1e-3, load = 0.5, reference = 1e-3;
  netmc::control::AdrcController adrc(gains, h);
  adrc.reset(0.0);
  double x = 0.0, v = 0.0, u = 0.0;
  for (int k = 0; k < 3000; ++k) {
    u = adrc.command(reference, x);
    adrc.commit(reference, x, u, u);
    // Exact zero-order-hold step of the double integrator.
    const double a = u + load;
    x += v * h + 0.5 * a * h * h;
    v += a * h;
  }
  std::printf("after 3 s: x = %.9f m (reference %.9f m), estimated load %.6f (true %.6f)\n", x, reference,
              adrc.observer().disturbance(), load);
  return std::abs(x - reference) < 1e-6 && std::abs(adrc.observer().disturbance() - load) < 1e-3 ? 0 : 1;
}
