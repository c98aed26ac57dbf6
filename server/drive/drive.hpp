#pragma once
// The seam between an axis node and its actuator. Above it, the node's DDS, job and safety logic
// (limits, watchdog, latched trips, sender checks, the CiA 402 master: SupervisedAxis); below it
// one Drive: netmc's simulated drive (sim:PLANT), a fieldbus drive (modbus-tcp:...) or a lab's
// plugin (plugin:....so). A drive speaks CiA 402: it takes controlwords and a mode of operation,
// takes targets in that mode and reports its statusword, error code and actual values. Values
// cross the seam in SI units (m, m/s, and the plant's input unit for torque); a drive converts
// to its own units below it.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "server/drive/axis_limits.hpp"

namespace netmc::drive {

// CiA 402 modes of operation (object 0x6060): cyclic synchronous position, velocity, torque.
enum class OperationMode : std::int8_t { csp = 8, csv = 9, cst = 10 };
const char* operation_mode_name(OperationMode mode);  // "csp", "csv", "cst"
std::optional<OperationMode> operation_mode_from_name(std::string_view name);
std::optional<OperationMode> operation_mode_from_code(std::int64_t code);

// One cyclic read of a drive.
struct DriveFeedback {
  double position_m = 0.0;       // actual position (0x6064)
  double velocity_m_s = 0.0;     // actual velocity (0x606C), where has_velocity
  bool has_velocity = false;
  std::uint16_t statusword = 0;  // 0x6041
  std::uint16_t error_code = 0;  // 0x603F
};

// A drive that cannot be reached, refuses a request or answers wrongly. The message names the
// object (or register) and the cause: "read of statusword (register 1): timeout after 20 ms".
class DriveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Drive {
 public:
  virtual ~Drive() = default;
  Drive(const Drive&) = delete;
  Drive& operator=(const Drive&) = delete;

  // What it is and where: "sim:seed001", "modbus-tcp:127.0.0.1:1502 unit 1".
  virtual std::string describe() const = 0;
  // The mode a job's commands are written in (CST for netmc's plants: the command is the
  // plant's input).
  virtual OperationMode job_mode() const { return OperationMode::cst; }
  // A simulation whose time moves only when cycle() says so: the node integrates it to each
  // sample instant and restarts it at rest between iterations (restart_at). Hardware runs on its
  // own time.
  virtual bool virtual_time() const { return false; }
  // Limits the drive's own configuration states (a map file); the operator's flags override them.
  virtual AxisLimits configured_limits() const { return {}; }

  // Connects and checks what can be checked before the first job; throws DriveError.
  virtual void open() = 0;
  // Leaves the drive with its power stage off where it can; never throws.
  virtual void close() noexcept = 0;

  virtual void write_controlword(std::uint16_t word) = 0;
  virtual void write_mode(OperationMode mode) = 0;
  // The target of `mode`: position (m), velocity (m/s) or torque (the plant's input unit).
  virtual void write_target(OperationMode mode, double value) = 0;
  virtual DriveFeedback read() = 0;
  // Called before every read of a sample and every positioning step with the node's job time
  // (s): a drive that needs a cyclic exchange does it here; a virtual-time simulation advances to
  // `time_s` with the inputs in force.
  virtual void cycle(double time_s) { (void)time_s; }
  // A simulation restarts at rest at `position_m` and says true; hardware cannot (false), and
  // the node moves it there.
  virtual bool restart_at(double position_m) {
    (void)position_m;
    return false;
  }
  // The longest a job's cycle may wait for the drive (s; 0: no budget, the drive's own
  // timeouts): a drive with a fieldbus bounds each exchange's wait by it and fails a cycle that
  // does not fit (DriveError naming the time and the budget). Others ignore it.
  virtual void set_cycle_budget(double budget_s) { (void)budget_s; }
  // Quick stop and fault reaction deceleration (0x6085), m/s^2.
  virtual void write_quick_stop_deceleration(double deceleration_m_s2) = 0;
  // What the drive measured of its own exchanges since the last call, for the node's log once
  // per iteration ("modbus round trip p50 180 us, p99 420 us, max 1.2 ms, 3210 requests"); empty
  // when it measures nothing.
  virtual std::string take_exchange_statistics() { return {}; }

 protected:
  Drive() = default;
};

}  // namespace netmc::drive
