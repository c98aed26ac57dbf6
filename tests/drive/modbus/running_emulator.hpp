#pragma once
// netmc-drive-emulator's server on a thread of the test's process (127.0.0.1, a port the system
// picks) and netmc's Modbus TCP master against it: what the Modbus drive's in-process tests share.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "server/drive/cia402.hpp"
#include "server/drive/emulated_drive.hpp"
#include "server/drive/emulator/drive_emulator.hpp"
#include "server/drive/modbus/modbus_tcp_drive.hpp"
#include "tests/drive/linear_servo_plant.hpp"

namespace netmc::drive {

using Clock = std::chrono::steady_clock;
using emulator::DriveEmulator;
using emulator::DriveEmulatorSettings;
using emulator::InjectedFault;
using modbus::ModbusTcpDrive;

inline double seconds_between(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

// An emulator serving on a thread of this process until destroyed.
class RunningEmulator {
 public:
  explicit RunningEmulator(DriveEmulatorSettings settings = quiet(), std::uint16_t port = 0) {
    settings.listen_host = "127.0.0.1";
    settings.listen_port = port;
    emulator_ = std::make_unique<DriveEmulator>(linear_servo_plant(), EmulatedDriveSettings{}, modbus::default_modbus_map(),
                                                settings);
    thread_ = std::thread([this] { emulator_->serve(stop_); });
  }
  ~RunningEmulator() {
    stop_.store(true);
    thread_.join();
  }
  std::uint16_t port() const { return emulator_->port(); }
  const DriveEmulator& emulator() const { return *emulator_; }

  // No watchdog: a test may pause without requests.
  static DriveEmulatorSettings quiet() {
    DriveEmulatorSettings settings;
    settings.watchdog_s = 0.0;
    return settings;
  }
  static DriveEmulatorSettings failing(InjectedFault::Kind kind, double after_s) {
    DriveEmulatorSettings settings = quiet();
    settings.fault = InjectedFault{after_s, kind};
    return settings;
  }

 private:
  std::atomic<bool> stop_{false};
  std::unique_ptr<DriveEmulator> emulator_;
  std::thread thread_;
};

inline std::unique_ptr<ModbusTcpDrive> master_of(std::uint16_t port, double timeout_s = 0.2,
                                          std::optional<std::uint8_t> unit = std::nullopt) {
  modbus::ModbusTcpSpec spec;
  spec.host = "127.0.0.1";
  spec.port = port;
  spec.timeout_s = timeout_s;
  spec.unit = unit;
  return std::make_unique<ModbusTcpDrive>(spec, modbus::default_modbus_map());
}

inline PowerState state_of(Drive& drive) {
  const auto state = decode_statusword(drive.read().statusword);
  EXPECT_TRUE(state.has_value());
  return state.value_or(PowerState::not_ready_to_switch_on);
}

// The master's way to Operation enabled: controlword_towards until there.
inline void enable(Drive& drive) {
  for (int step = 0; step < 5; ++step) {
    const auto word = controlword_towards(state_of(drive), PowerState::operation_enabled);
    if (!word) break;
    drive.write_controlword(*word);
  }
  ASSERT_EQ(state_of(drive), PowerState::operation_enabled);
}

// Reads until `done` holds, at most `limit_s`; true if it held.
inline bool eventually(Drive& drive, const std::function<bool(const DriveFeedback&)>& done, double limit_s = 1.5) {
  const auto end = Clock::now() + std::chrono::duration<double>(limit_s);
  while (Clock::now() < end) {
    if (done(drive.read())) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

// The message of the DriveError `call` throws; fails the test if it does not.
inline std::string drive_error(const std::function<void()>& call) {
  try {
    call();
  } catch (const DriveError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no DriveError";
  return {};
}

}  // namespace netmc::drive
