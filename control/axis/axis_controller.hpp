#pragma once
// Per-axis feedback controller seen by the contouring layer. A cycle is two calls: command()
// computes u(k) from the state the controller holds, commit() then advances that state with the
// measurement and the command actually sent (which may include a cross-coupling term).

#include <memory>
#include <string>

namespace netmc::control {

class AxisController {
 public:
  virtual ~AxisController() = default;

  // Start of a run (every ILC iteration): the axis rests at `position`.
  virtual void reset(double position) = 0;
  // u(k) for reference x_d(k) and measured position y(k). Does not change the state.
  virtual double command(double reference, double measured_position) const = 0;
  // Advance internal filters with y(k), the controller's own u(k) and the command U(k) that was
  // sent to the axis.
  virtual void commit(double reference, double measured_position, double own_command,
                      double sent_command) = 0;

  virtual std::unique_ptr<AxisController> clone() const = 0;
  virtual std::string describe() const = 0;
};

}  // namespace netmc::control
