#pragma once
// Linear ADRC for one axis (paper 001, eq. 8-10): tracking differentiator on the reference,
// extended state observer on the measurement, PD state-error feedback and cancellation of the
// estimated total disturbance.

#include "control/axis/axis_controller.hpp"
#include "control/axis/extended_state_observer.hpp"
#include "control/axis/tracking_differentiator.hpp"

namespace netmc::control {

struct AdrcGains {
  double td_speed_factor = 160.0;       // r0 [1/s]
  double observer_bandwidth = 100.0;    // w0 [rad/s]
  double input_gain = 20.0;             // b0
  double kp = 0.08;                     // on v1 - z1
  double kd = 6.0;                      // on v2 - z2
  Discretization observer_discretization = Discretization::forward_euler;
  // The paper's eq. 9 is driven by the ADRC output u_i; the cross-coupling term is then part of
  // the total disturbance. true feeds the observer the command actually sent, U_i.
  bool observer_sees_sent_command = false;
};

class AdrcController final : public AxisController {
 public:
  AdrcController(const AdrcGains& gains, double sample_period_s);

  void reset(double position) override;
  double command(double reference, double measured_position) const override;
  void commit(double reference, double measured_position, double own_command,
              double sent_command) override;
  std::unique_ptr<AxisController> clone() const override;
  std::string describe() const override;

  const ExtendedStateObserver& observer() const { return observer_; }
  const TrackingDifferentiator& differentiator() const { return differentiator_; }

 private:
  AdrcGains gains_;
  TrackingDifferentiator differentiator_;
  ExtendedStateObserver observer_;
};

}  // namespace netmc::control
