#pragma once
// One co-simulation instance of a loaded FMU (an fmi2Component), with the calls netmc makes,
// each checked: a status of fmi2Discard or worse (FMI 2.0, 2.1.3; fmi2Pending too, netmc never
// asks for an asynchronous step) throws std::runtime_error naming the FMU, the call, the
// variable where there is one, the time and the status, with the FMU's last logged message.
// After fmi2Fatal the whole model is marked (FmuModel::mark_fatal) and no further call is made.
// Freed with fmi2Terminate (when initialised) and fmi2FreeInstance.

#include <memory>
#include <string>

#include "server/fmu/fmi2_api.h"
#include "server/fmu/fmu_model.hpp"

namespace netmc::plant::fmu {

// A Real variable as netmc calls it.
struct RealVariable {
  std::string name;
  fmi2ValueReference value_reference = 0;
};

class FmuInstance {
 public:
  // fmi2Instantiate as a co-simulation instance named `instance_name`.
  FmuInstance(std::shared_ptr<FmuModel> model, std::string instance_name);
  ~FmuInstance();
  FmuInstance(const FmuInstance&) = delete;
  FmuInstance& operator=(const FmuInstance&) = delete;

  // fmi2Reset: back to the state right after fmi2Instantiate (FMI 2.0, 2.1.6). False (nothing
  // thrown) when the FMU refuses: the caller then makes a new instance.
  bool reset() noexcept;
  // FMI 2.0, 2.1.6: no tolerance, no stop time, start at start_time_s.
  void setup_experiment(double start_time_s);
  void enter_initialization_mode();
  void exit_initialization_mode();
  void set_real(const RealVariable& variable, double value, double time_s);
  double get_real(const RealVariable& variable, double time_s);
  // FMI 2.0, 4.2.2, with noSetFMUStatePriorToCurrentPoint = true: netmc never goes back in time.
  void do_step(double time_s, double step_s);

  const FmuModel& model() const { return *model_; }

 private:
  // Throws for a failed call; `what` names the call and its argument.
  [[noreturn]] void fail(fmi2Status status, const std::string& what, double time_s);
  void require_usable(const char* call) const;

  std::shared_ptr<FmuModel> model_;
  std::string name_;
  fmi2Component component_ = nullptr;
  bool initialised_ = false;
  bool errored_ = false;  // fmi2Error (or worse) seen since the last reset
  double start_time_s_ = 0.0;
};

}  // namespace netmc::plant::fmu
