#pragma once
// Plain discrete PID position loop for one axis, the baseline per-axis controller beside ADRC.

#include "control/axis/axis_controller.hpp"

namespace netmc::control {

struct PidAxisGains {
  double kp = 0.0;   // per m of position error
  double ki = 0.0;   // per m*s
  double kd = 0.0;   // per m/s (backward difference of the error)
};

class PidAxisController final : public AxisController {
 public:
  PidAxisController(const PidAxisGains& gains, double sample_period_s);

  void reset(double position) override;
  double command(double reference, double measured_position) const override;
  void commit(double reference, double measured_position, double own_command,
              double sent_command) override;
  std::unique_ptr<AxisController> clone() const override;
  std::string describe() const override;

 private:
  PidAxisGains gains_;
  double h_;
  double integral_ = 0.0;
  double previous_error_ = 0.0;
};

}  // namespace netmc::control
