#pragma once
// PID cross-coupled controller (the "ADRC+PIDCCC" baseline of paper 001): u_e from the contour
// error of the current cycle, discretized like eq. 14 (difference without division by h).

#include "control/cross_coupling/contour_compensator.hpp"

namespace netmc::control {

struct PidCrossCouplingGains {
  double kp = 500.0;
  double ki = 0.0;
  double kd = 50.0;
};

class PidCrossCoupling final : public ContourCompensator {
 public:
  PidCrossCoupling(const PidCrossCouplingGains& gains, double sample_period_s);

  void begin_iteration(std::size_t samples) override;
  double command(std::size_t cycle, double contour_error) override;
  std::unique_ptr<ContourCompensator> clone() const override;
  std::string describe() const override;

 private:
  PidCrossCouplingGains gains_;
  double h_;
  double integral_ = 0.0;
  double previous_error_ = 0.0;
};

}  // namespace netmc::control
