// netmc's example component plugin: a researcher's own per-axis law and plant in C++, loaded by
// netmc with --controller plugin:PATH.so:kp=..,kd=.. and --plant plugin:PATH.so[:a2=..,b=..].
//
// - The axis controller is a PD position loop, u(k) = kp e(k) + kd (e(k) - e(k-1)) / h with
//   e = reference - measured position: netmc's built-in PID loop (control/axis/pid_axis_controller.cpp)
//   with ki = 0, written with the same operations in the same order, so it gives the same
//   commands as `pid` with ki = 0, bit for bit (but for the sign of an exactly zero command, where
//   the PID's zero integral term turns -0 into +0).
// - The plant is paper 001's servo axis in speed mode without friction, x'' = a2 x' + b u
//   (seed001's X axis: a2 = -20 1/s, b = 20; its Y and third axes: -10, 10), made of netmc's own
//   model, netmc::plant::SecondOrderAxis: a plugin may link netmc's libraries.
//
// The whole contract is in <netmc/control/plugin/component_plugin.hpp>. Replace either part with your
// own law or model; keep the NETMC_COMPONENT_PLUGIN line at the end (nullptr for a part you do
// not provide).
#include <netmc/control/plugin/component_plugin.hpp>
#include <netmc/plant/second_order_axis.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

using netmc::control::ComponentSettings;

// Refuses a key the factory does not know, naming the ones it does: a typo must not pass
// silently as a default.
void refuse_unknown_keys(const ComponentSettings& settings, std::initializer_list<const char*> known,
                         const std::string& owner) {
  for (const auto& [key, value] : settings) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string names;
      for (const char* name : known) names += (names.empty() ? "" : ", ") + std::string(name);
      throw std::invalid_argument(owner + ": unknown key '" + key + "' (it takes " + names + ")");
    }
  }
}

double required(const ComponentSettings& settings, const std::string& key, const std::string& owner) {
  const auto it = settings.find(key);
  if (it == settings.end()) throw std::invalid_argument(owner + ": " + key + " is required");
  return it->second;
}

double optional(const ComponentSettings& settings, const std::string& key, double fallback) {
  const auto it = settings.find(key);
  return it == settings.end() ? fallback : it->second;
}

// The PD loop. Its state is the previous error; command() reads it, commit() advances it.
class PdAxisLoop final : public netmc::control::AxisController {
 public:
  PdAxisLoop(double kp, double kd, double sample_period_s) : kp_(kp), kd_(kd), h_(sample_period_s) {}

  void reset(double /*position*/) override { previous_error_ = 0.0; }

  double command(double reference, double measured_position) const override {
    const double error = reference - measured_position;
    return kp_ * error + kd_ * (error - previous_error_) / h_;
  }

  void commit(double reference, double measured_position, double /*own_command*/,
              double /*sent_command*/) override {
    previous_error_ = reference - measured_position;
  }

  std::unique_ptr<netmc::control::AxisController> clone() const override {
    return std::make_unique<PdAxisLoop>(*this);
  }

  std::string describe() const override {
    std::ostringstream text;
    text << "example pd(kp=" << kp_ << ", kd=" << kd_ << ")";
    return text.str();
  }

 private:
  double kp_;
  double kd_;
  double h_;
  double previous_error_ = 0.0;
};

std::unique_ptr<netmc::control::AxisController> make_pd_loop(const ComponentSettings& settings,
                                                             std::size_t /*axis_index*/, double sample_period_s) {
  const std::string owner = "example pd";
  refuse_unknown_keys(settings, {"kp", "kd"}, owner);
  if (!(sample_period_s > 0.0) || !std::isfinite(sample_period_s)) {
    throw std::invalid_argument(owner + ": the sample period must be positive and finite");
  }
  return std::make_unique<PdAxisLoop>(required(settings, "kp", owner), required(settings, "kd", owner),
                                      sample_period_s);
}

std::unique_ptr<netmc::plant::AxisPlant> make_servo_axis(const ComponentSettings& settings, std::size_t axis_index) {
  const std::string owner = "example servo axis";
  refuse_unknown_keys(settings, {"a2", "b"}, owner);
  if (axis_index > 2) throw std::invalid_argument(owner + ": axis " + std::to_string(axis_index) + " (0, 1 or 2)");
  netmc::plant::SecondOrderAxisParameters p;  // no friction, no disturbance: linear, integrated exactly
  p.a1 = 0.0;
  p.coulomb_velocity_scale = 1e-3;  // unused without friction; seed001's values, so describe() reads as its
  p.max_substep_s = 1e-3;
  p.a2 = optional(settings, "a2", axis_index == 0 ? -20.0 : -10.0);
  p.b = optional(settings, "b", axis_index == 0 ? 20.0 : 10.0);
  if (p.a2 > 0.0) throw std::invalid_argument(owner + ": a2 must be <= 0 (a damped axis)");
  if (!(p.b > 0.0)) throw std::invalid_argument(owner + ": b must be positive");
  return std::make_unique<netmc::plant::SecondOrderAxis>(p);
}

std::string describe() {
  return "netmc example: PD axis loop (kp, kd) and paper 001's servo axis x'' = a2 x' + b u (a2, b)";
}

}  // namespace

NETMC_COMPONENT_PLUGIN(describe, make_pd_loop, make_servo_axis)
