#pragma once
// An axis plant that is an FMU (FMI 2.0 co-simulation): one instance of the model per plant
// object, driven through the AxisPlant interface.
//
//   reset(x, v)    fmi2Reset (a new instance if the FMU refuses it), the parameters, the start
//                  position and velocity into their variables (position_start / velocity_start),
//                  fmi2SetupExperiment at t = 0, fmi2Enter/ExitInitializationMode. Without a
//                  position_start variable the FMU always starts where its own start values put
//                  it, and only that position is accepted (std::invalid_argument otherwise); the
//                  same for the velocity (at rest, or its velocity output's initial value).
//   advance(d, u)  u into the input, then fmi2DoStep over [t, t + d) in equal steps of at most
//                  `step` (exactly `step` each, and d a whole number of them, for an FMU that
//                  cannot vary its communication step); d = 0 calls nothing.
//   position()     the output after the last step; velocity() the velocity output, or without
//                  one the difference quotient of the position over the last fmi2DoStep (after
//                  reset(): the velocity_start variable's value, else 0).
//   clone()        FMI 2.0 gives no way to carry an FMU state from one instance into another
//                  (fmi2GetFMUstate/fmi2SetFMUstate work within one instance), so a clone is a new
//                  instance initialised as the original was at its last reset() and replayed
//                  through the same advance() calls since: deterministic models end in the same
//                  state, bit for bit. The replay list is bounded (kMaxReplayedAdvances); past it
//                  clone() throws std::runtime_error. netmc clones plants as prototypes (never
//                  advanced) and probes (right after construction), well inside the bound.
//
// A plant instantiates lazily: it is made with a probe (one instance, initialised with the FMU's
// own start values, then freed) that checks its parameters and learns its initial outputs, and
// holds an instance only from its first reset() or advance(); a prototype that is only cloned
// holds none (which lets a model that can be instantiated only once per process run one axis).
//
// Failures: an FMU call that fails throws std::runtime_error (naming the call, the time and the
// status; FmuInstance), so does a non-finite output; the plant then refuses advance() and clone()
// until reset() succeeds.
//
// What cannot be caught: the FMU's code runs inside netmc's process. A crash in it (a segfault,
// an abort, an endless loop in fmi2DoStep) takes the process with it or hangs it. In netmc-axis
// the node is the unit of failure: the server's silence limit sees the node go quiet and stops
// the job, and a real drive's own watchdog stops the axis. In `netmc sim` the study stops.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "plant/axis_plant.hpp"
#include "server/fmu/fmu_instance.hpp"
#include "server/fmu/fmu_model.hpp"

namespace netmc::plant::fmu {

inline constexpr std::size_t kMaxReplayedAdvances = 100000;

// What an FmuAxisPlant runs, resolved against the FMU's description (fmu_plant_set.cpp).
struct FmuAxisSetup {
  std::shared_ptr<FmuModel> model;
  std::size_t axis = 0;
  std::string options_text;  // what followed "fmu:", for describe()
  RealVariable input;
  RealVariable output;
  std::optional<RealVariable> velocity;
  std::optional<RealVariable> position_start;
  std::optional<RealVariable> velocity_start;
  double step_s = 1e-3;
  bool fixed_step = false;  // the FMU cannot handle a variable communication step size
  std::vector<std::pair<RealVariable, double>> parameters;  // set before initialisation, in order
};

class FmuAxisPlant final : public AxisPlant {
 public:
  // Probes the setup (see above); throws what the probe's calls throw.
  explicit FmuAxisPlant(std::shared_ptr<const FmuAxisSetup> setup);
  ~FmuAxisPlant() override;
  FmuAxisPlant(const FmuAxisPlant&) = delete;
  FmuAxisPlant& operator=(const FmuAxisPlant&) = delete;

  void reset(double position, double velocity) override;
  void advance(double duration_s, double input) override;
  double position() const override { return position_; }
  double velocity() const override { return velocity_; }
  double time() const override { return time_; }
  std::unique_ptr<AxisPlant> clone() const override;
  std::string describe() const override;

  const FmuAxisSetup& setup() const { return *setup_; }
  // True while the plant holds an FMU instance.
  bool instantiated() const { return instance_ != nullptr; }

 private:
  struct Start {
    double position = 0.0, velocity = 0.0;
  };
  struct Advance {
    double duration_s = 0.0, input = 0.0;
  };
  struct Unprobed {};
  FmuAxisPlant(std::shared_ptr<const FmuAxisSetup> setup, Unprobed);

  // An instance initialised with the parameters and `start` (the FMU's own start when empty).
  void initialise(const std::optional<Start>& start);
  void read_outputs(double previous_position, double step_s);
  [[noreturn]] void fail(const std::string& why) const;
  std::string name() const;

  std::shared_ptr<const FmuAxisSetup> setup_;
  std::unique_ptr<FmuInstance> instance_;
  double position_ = 0.0, velocity_ = 0.0, time_ = 0.0;
  // Where the FMU's own start values put it (the probe's outputs).
  double default_position_ = 0.0, default_velocity_ = 0.0;
  std::optional<Start> start_;  // of the last reset(); empty: the FMU's own start
  bool broken_ = false;         // a call failed: only reset() is taken
  std::vector<Advance> history_;  // advance() calls since the last reset, for clone()
  bool history_overflowed_ = false;
};

}  // namespace netmc::plant::fmu
