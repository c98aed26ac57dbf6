#pragma once
// The Modbus TCP server of netmc-drive-emulator: one axis of a netmc plant behind a CiA 402 drive
// (an EmulatedDrive, the same code netmc's simulated drive runs) and a register map, in real
// time. The drive's time is CLOCK_MONOTONIC since construction: before every request and at every
// tick of its cycle the drive is integrated to now, so a target acts from the instant it arrives.
//
// One master at a time; a new connection replaces the older one. Frames are cut by the MBAP
// header's length without ever blocking (a master that sends half a frame stalls nothing), then
// checked field by field before libmodbus composes the answer. The drive's own fieldbus watchdog:
// in Operation enabled, no request for `watchdog_s` is a fault (error code 0x8100), raised at the
// instant the watchdog ran out whenever the emulator notices it.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "plant/axis_plant.hpp"
#include "server/drive/emulated_drive.hpp"
#include "server/drive/emulator/emulated_registers.hpp"
#include "server/drive/emulator/injected_fault.hpp"
#include "server/drive/modbus/modbus_map.hpp"

struct _modbus;          // libmodbus's context (modbus_t)
struct _modbus_mapping_t;  // libmodbus's register image (modbus_mapping_t)

namespace netmc::drive::emulator {

struct DriveEmulatorSettings {
  std::string listen_host = "127.0.0.1";  // an IPv4 address
  std::uint16_t listen_port = 1502;       // 0: the system picks one (port())
  std::optional<std::uint8_t> unit;       // the unit it answers; default the map's unit_id
  double watchdog_s = 0.1;                // 0: no watchdog
  double initial_position_m = 0.0;        // where the axis rests at start
  std::optional<InjectedFault> fault;
};

class DriveEmulator {
 public:
  using Clock = std::chrono::steady_clock;

  // Listens at once. Throws std::invalid_argument for bad settings or a plant the drive cannot
  // tune its loops to, std::runtime_error when it cannot listen.
  DriveEmulator(std::unique_ptr<plant::AxisPlant> plant, EmulatedDriveSettings drive_settings, modbus::ModbusMap map,
                DriveEmulatorSettings settings);
  ~DriveEmulator();
  DriveEmulator(const DriveEmulator&) = delete;
  DriveEmulator& operator=(const DriveEmulator&) = delete;

  std::uint16_t port() const { return port_; }
  std::string address() const;  // "127.0.0.1:1502"
  std::uint8_t unit() const { return unit_; }

  // The drive's actual position when it was last advanced, whatever its registers say (the
  // frozen fault): for a test on another thread.
  double actual_position_m() const { return actual_position_m_.load(); }

  // Serves until `stop` is set (seen within one cycle), then closes the master's connection.
  void serve(const std::atomic<bool>& stop);

 private:
  double now_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  // The drive at `now`: the watchdog first (a fault at the instant it ran out), then the rest.
  void advance(double now);
  void log_state_change();
  void accept_master();
  void read_master();
  void close_master(const std::string& why);
  // Handles every whole frame in the buffer (or closes a connection that is not Modbus TCP).
  void handle_frames();
  void handle_request(std::uint8_t* frame, std::size_t size);
  // Answers with libmodbus; `frame` is the request (its unit byte the one to answer with).
  void reply(const std::uint8_t* frame, std::size_t size);
  void reply_exception(const std::uint8_t* frame, std::uint8_t code, const std::string& why);
  // The frozen fault: the actual position and velocity in `words` (registers from `address`) as
  // they were when it began.
  void freeze_feedback(std::uint16_t address, std::uint16_t count, std::uint16_t* words);

  modbus::ModbusMap map_;
  EmulatedDrive drive_;
  EmulatedRegisters registers_;
  DriveEmulatorSettings settings_;
  std::uint8_t unit_;
  Clock::time_point start_;
  _modbus* context_ = nullptr;
  _modbus_mapping_t* image_ = nullptr;  // the map's span of holding registers, for libmodbus's replies
  std::uint16_t image_start_ = 0;
  int listen_socket_ = -1;
  int master_socket_ = -1;
  std::uint16_t port_ = 0;
  std::string master_name_;
  std::array<std::uint8_t, 520> buffer_{};  // two whole frames (260 bytes each)
  std::size_t buffered_ = 0;
  double last_request_s_ = 0.0;
  std::optional<double> first_connection_s_;
  bool fault_announced_ = false;
  PowerState logged_state_;
  std::uint64_t requests_ = 0;
  std::uint64_t refusals_ = 0;
  double refusal_logged_s_ = -1.0;  // refusals are logged at most once a second
  std::uint64_t refusals_unlogged_ = 0;
  // The frozen fault's registers (address, word), captured when it began.
  std::vector<std::pair<std::uint16_t, std::uint16_t>> frozen_words_;
  std::atomic<double> actual_position_m_{0.0};
};

}  // namespace netmc::drive::emulator
