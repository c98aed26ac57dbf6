#pragma once
// A CiA 402 servo drive around one of netmc's plant models: the device side of the power state
// machine, the three cyclic synchronous modes and the ramps a drive runs by itself. netmc's
// simulated drive (sim:PLANT) runs it in virtual time; netmc-drive-emulator runs it in real time
// behind Modbus TCP. Time is whatever its owner says (advance_to); both call the same code.
//
// In Operation enabled with CST the torque target is the plant's input, held between writes, and
// nothing else happens: that is netmc's plant as every study drives it (paper 001, eq. 4). The
// drive's own loops run on its cycle (cycle_s) only where they act: CSV (a PI velocity loop), CSP
// (a proportional position loop with the targets' velocity fed forward, over the velocity loop)
// and the quick stop and fault reaction ramps, which bring the velocity to zero at the quick stop
// deceleration and end at standstill. The velocity loop's gain comes from a probe of the plant's
// response to its input at construction, so any plant gets a loop of the set bandwidth.

#include <limits>
#include <memory>

#include "plant/axis_plant.hpp"
#include "server/drive/drive.hpp"
#include "server/drive/power_state_machine.hpp"

namespace netmc::drive {

struct EmulatedDriveSettings {
  // Largest |plant input| the power stage gives (max torque, 0x6072): clamps the CST target and
  // every loop. Infinite: an ideal stage, as the studies' plants are (a job's command_limit is
  // their saturation).
  double max_input = std::numeric_limits<double>::infinity();
  double quick_stop_deceleration_m_s2 = 1.0;  // 0x6085, also the fault reaction's
  double cycle_s = 250e-6;                    // period of the drive's own loops
  double velocity_loop_hz = 40.0;             // bandwidth of its velocity loop
  double standstill_velocity_m_s = 1e-3;      // a ramp ends below this speed
  double position_window_m = 1e-6;            // CSP: target reached within this

  // Throws std::invalid_argument naming the setting for a non-positive or non-finite value.
  void validate() const;
};

class EmulatedDrive {
 public:
  // Throws std::invalid_argument if the plant does not respond to its input (a probe from rest
  // with +-input gives no acceleration): the drive's loops could not be tuned.
  EmulatedDrive(std::unique_ptr<plant::AxisPlant> plant, EmulatedDriveSettings settings);

  // Initialisation done: Switch on disabled (transition 1).
  void power_up() { machine_.initialised(); }
  // At rest at `position_m`, time 0, targets zero; the power state stays.
  void restart_at(double position_m);
  // Runs the plant and the drive's loops to `time_s` (a time before the drive's is ignored).
  void advance_to(double time_s);

  void apply_controlword(std::uint16_t word);
  void set_mode(OperationMode mode);
  void set_target(OperationMode mode, double value);
  void set_quick_stop_deceleration(double deceleration_m_s2);
  // A fault the drive detects (its fieldbus watchdog, a broken model): fault reaction, then Fault.
  void raise_fault(std::uint16_t error_code);
  // A model whose state is no longer finite faults (0xFF01); checked where the drive is read,
  // not in every step of the plant.
  void check_model();

  PowerState state() const { return machine_.state(); }
  std::uint16_t statusword() const;
  std::uint16_t error_code() const { return machine_.error_code(); }
  OperationMode mode() const { return mode_; }
  double time() const { return time_; }
  double position() const { return plant_->position(); }
  double velocity() const { return plant_->velocity(); }
  double input() const { return input_; }
  // Acceleration per unit of input the probe measured (for the tests and the log).
  double input_gain() const { return input_gain_; }
  const plant::AxisPlant& plant() const { return *plant_; }
  const EmulatedDriveSettings& settings() const { return settings_; }

 private:
  bool loops_active() const;
  void start_ramp();
  void run_loops();  // one drive cycle: the loop of the state and mode in force
  double velocity_loop(double velocity_reference, double acceleration_feedforward);
  double clamp_input(double input) const;

  std::unique_ptr<plant::AxisPlant> plant_;
  EmulatedDriveSettings settings_;
  PowerStateMachine machine_;
  OperationMode mode_ = OperationMode::cst;
  double input_gain_ = 0.0;       // m/s^2 per input unit
  double time_ = 0.0;
  double next_cycle_ = 0.0;
  double input_ = 0.0;            // the plant's input now
  double target_position_m_ = 0.0;
  double target_velocity_m_s_ = 0.0;
  double target_torque_ = 0.0;
  double feedforward_velocity_m_s_ = 0.0;  // CSP: the targets' own velocity
  double last_target_time_ = -std::numeric_limits<double>::infinity();
  double target_interval_s_ = 0.0;         // between the last two CSP targets
  double velocity_integral_ = 0.0;
  double ramp_start_time_ = 0.0;
  double ramp_start_velocity_ = 0.0;
};

}  // namespace netmc::drive
