// netmc's Modbus TCP master against netmc-drive-emulator's server, both in this process on
// 127.0.0.1 (the server on a thread, on a port the system picks): the CiA 402 sequence, the three
// modes, the quick stop, the drive's watchdog, every fault the emulator can inject, a dropped
// connection and hostile frames. Time is real: bounds are generous, and each test stays under
// two seconds.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "plant/second_order_axis.hpp"
#include "server/drive/cia402.hpp"
#include "server/drive/emulated_drive.hpp"
#include "server/drive/emulator/drive_emulator.hpp"
#include "server/drive/modbus/modbus_tcp_drive.hpp"
#include "tests/drive/power_state_printer.hpp"
#include "tests/drive/linear_servo_plant.hpp"
#include "tests/drive/modbus/running_emulator.hpp"

namespace netmc::drive {
namespace {

// The drive the emulator runs, driven directly: enabled in CST with `torque` from rest at 0, run
// for `elapsed_s`.
EmulatedDrive reference_drive(double torque, double elapsed_s) {
  EmulatedDrive drive(linear_servo_plant(), EmulatedDriveSettings{});
  drive.power_up();
  drive.restart_at(0.0);
  drive.apply_controlword(controlword::shutdown);
  drive.apply_controlword(controlword::enable_operation);
  drive.set_mode(OperationMode::cst);
  drive.set_target(OperationMode::cst, torque);
  drive.advance_to(elapsed_s);
  return drive;
}

TEST(ModbusLoopback, OpensEnablesAndACstTargetMovesThePlantAsTheEmulatedDriveWould) {
  RunningEmulator emulator;
  const auto master = master_of(emulator.port());
  EXPECT_EQ(master->describe(), "modbus-tcp:127.0.0.1:" + std::to_string(emulator.port()) + " unit 1");
  master->open();
  EXPECT_EQ(state_of(*master), PowerState::switch_on_disabled);
  enable(*master);
  master->write_mode(OperationMode::cst);
  master->write_quick_stop_deceleration(5.0);
  const DriveFeedback rest = master->read();
  EXPECT_EQ(rest.position_m, 0.0);
  EXPECT_TRUE(rest.has_velocity);
  // The target acted from some instant within the write's round trip; the read saw the plant at
  // some instant within its own: the motion lies between the two extreme intervals.
  const double torque = 0.5;
  const auto write_sent = Clock::now();
  master->write_target(OperationMode::cst, torque);
  const auto write_answered = Clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  master->take_exchange_statistics();
  const auto read_sent = Clock::now();
  const DriveFeedback moved = master->read();
  const auto read_answered = Clock::now();
  // One request per sample with the default map.
  const std::string statistics = master->take_exchange_statistics();
  EXPECT_EQ(statistics.rfind("modbus round trip p50 ", 0), 0u) << statistics;
  EXPECT_NE(statistics.find(", 1 request"), std::string::npos) << statistics;
  EXPECT_EQ(master->take_exchange_statistics(), "");
  const EmulatedDrive least = reference_drive(torque, seconds_between(write_answered, read_sent));
  const EmulatedDrive most = reference_drive(torque, seconds_between(write_sent, read_answered));
  EXPECT_GE(moved.position_m, least.position() - 2e-9);
  EXPECT_LE(moved.position_m, most.position() + 2e-9);
  EXPECT_GE(moved.velocity_m_s, least.velocity() - 2e-6);
  EXPECT_LE(moved.velocity_m_s, most.velocity() + 2e-6);
  EXPECT_GT(moved.position_m, 0.01);  // it did move: 150 ms at up to 0.5 m/s
  EXPECT_EQ(decode_statusword(moved.statusword), PowerState::operation_enabled);
  EXPECT_EQ(moved.error_code, 0);
}

TEST(ModbusLoopback, ACspTargetIsReached) {
  RunningEmulator emulator;
  const auto master = master_of(emulator.port());
  master->open();
  enable(*master);
  master->write_mode(OperationMode::csp);
  master->write_target(OperationMode::csp, 0.002);
  EXPECT_TRUE(eventually(*master, [](const DriveFeedback& feedback) {
    return (feedback.statusword & statusword::target_reached) && std::abs(feedback.position_m - 0.002) <= 2e-6;
  })) << master->read().position_m;
}

TEST(ModbusLoopback, AQuickStopRampsToStandstillAndEndsInSwitchOnDisabled) {
  RunningEmulator emulator;
  const auto master = master_of(emulator.port());
  master->open();
  enable(*master);
  master->write_mode(OperationMode::cst);
  master->write_quick_stop_deceleration(4.0);
  master->write_target(OperationMode::cst, 1.0);
  ASSERT_TRUE(eventually(*master, [](const DriveFeedback& feedback) { return feedback.velocity_m_s > 0.3; }));
  master->write_controlword(controlword::quick_stop);
  EXPECT_EQ(state_of(*master), PowerState::quick_stop_active);
  ASSERT_TRUE(eventually(*master, [](const DriveFeedback& feedback) {
    return decode_statusword(feedback.statusword) == PowerState::switch_on_disabled;
  }));
  EXPECT_LT(std::abs(master->read().velocity_m_s), 2e-3);
}

TEST(ModbusLoopback, TheDrivesWatchdogFaultsASilentMasterAndBit7sRisingEdgeResetsIt) {
  DriveEmulatorSettings settings;
  settings.watchdog_s = 0.1;
  RunningEmulator emulator(settings);
  const auto master = master_of(emulator.port());
  master->open();
  enable(*master);
  std::this_thread::sleep_for(std::chrono::milliseconds(250));  // no request: the watchdog runs out
  const DriveFeedback faulted = master->read();
  EXPECT_EQ(decode_statusword(faulted.statusword), PowerState::fault);
  EXPECT_EQ(faulted.error_code, error_code::communication);
  master->write_controlword(controlword::fault_reset);  // bit 7 rises
  const DriveFeedback reset = master->read();
  EXPECT_EQ(decode_statusword(reset.statusword), PowerState::switch_on_disabled);
  EXPECT_EQ(reset.error_code, error_code::none);
  enable(*master);  // and the sequence runs again
}

TEST(ModbusLoopback, AnInjectedExceptionIsNamed) {
  RunningEmulator emulator(RunningEmulator::failing(InjectedFault::Kind::exception, 0.0));
  const auto master = master_of(emulator.port());
  EXPECT_EQ(drive_error([&] { master->open(); }),
            "read of input block (registers 0-6: statusword, modes_of_operation_display, error_code, "
            "position_actual, velocity_actual): Modbus exception 4 (server device failure)");
}

TEST(ModbusLoopback, AnAnswerFromAnotherUnitIsNamed) {
  RunningEmulator emulator(RunningEmulator::failing(InjectedFault::Kind::wrong_unit, 0.0));
  const auto master = master_of(emulator.port());
  const std::string message = drive_error([&] { master->open(); });
  EXPECT_NE(message.find("read of input block (registers 0-6: "), std::string::npos) << message;
  EXPECT_NE(message.find(": answer from unit 2 (asked unit 1)"), std::string::npos) << message;
}

TEST(ModbusLoopback, ASilentDriveTimesOut) {
  RunningEmulator emulator(RunningEmulator::failing(InjectedFault::Kind::silence, 0.0));
  const auto master = master_of(emulator.port(), 0.05);
  const auto start = Clock::now();
  const std::string message = drive_error([&] { master->open(); });
  EXPECT_NE(message.find("read of input block (registers 0-6: "), std::string::npos) << message;
  EXPECT_NE(message.find(": timeout after 50 ms"), std::string::npos) << message;
  EXPECT_LT(seconds_between(start, Clock::now()), 1.0);
}

TEST(ModbusLoopback, AFaultInjectedLaterBreaksACycleThatWorked) {
  RunningEmulator emulator(RunningEmulator::failing(InjectedFault::Kind::exception, 0.2));
  const auto master = master_of(emulator.port());
  master->open();
  const std::string message = drive_error([&] {
    const auto end = Clock::now() + std::chrono::milliseconds(1500);
    while (Clock::now() < end) {
      master->read();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });
  EXPECT_NE(message.find("Modbus exception 4 (server device failure)"), std::string::npos) << message;
  // An exception is an answer: the connection stays.
  EXPECT_TRUE(master->connected());
}

TEST(ModbusLoopback, RequestsTheDriveRefusesAreNamedAndValuesOutOfRangeAreNotSent) {
  RunningEmulator emulator;
  const auto master = master_of(emulator.port());
  master->open();
  EXPECT_EQ(drive_error([&] { master->write_mode(static_cast<OperationMode>(7)); }),
            "write of modes_of_operation (register 17): Modbus exception 3 (illegal data value)");
  EXPECT_EQ(drive_error([&] { master->write_target(OperationMode::csp, 3.0); }),
            "write of target_position (registers 18-19): 3 m does not fit int32 at 1e+09 counts per metre (range "
            "-2.14748 to 2.14748 m)");
  EXPECT_EQ(state_of(*master), PowerState::switch_on_disabled);  // still connected
  const auto stranger = master_of(emulator.port(), 0.2, std::uint8_t{5});
  EXPECT_NE(drive_error([&] { stranger->open(); }).find("Modbus exception 11 (gateway target device failed to respond)"),
            std::string::npos);
}

TEST(ModbusLoopback, AnUnreachableDriveFailsToOpen) {
  // A port nothing listens on: bound, then closed again.
  const int probe = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof address;
  ASSERT_EQ(::bind(probe, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ::getsockname(probe, reinterpret_cast<sockaddr*>(&address), &length);
  const std::uint16_t port = ntohs(address.sin_port);
  ::close(probe);
  const auto master = master_of(port);
  EXPECT_EQ(drive_error([&] { master->open(); }),
            "open: connect to 127.0.0.1:" + std::to_string(port) + ": connection refused");
  // The next call within 200 ms does not try again.
  const std::string waiting = drive_error([&] { master->read(); });
  EXPECT_NE(waiting.find(": not connected (connect to 127.0.0.1:" + std::to_string(port) +
                         ": connection refused); next attempt in "),
            std::string::npos)
      << waiting;
}

TEST(ModbusLoopback, AfterADroppedConnectionTheMasterConnectsAgainAtMostEvery200Ms) {
  auto first = std::make_unique<RunningEmulator>();
  const std::uint16_t port = first->port();
  const auto master = master_of(port);
  master->open();
  enable(*master);
  first.reset();  // the drive goes away: its end of the connection closes
  const std::string dropped = drive_error([&] { master->read(); });
  EXPECT_NE(dropped.find("read of input block (registers 0-6: "), std::string::npos) << dropped;
  EXPECT_FALSE(master->connected());
  std::string waiting = drive_error([&] { master->read(); });
  // On a slow machine that call may have been a (failed) attempt already; the next one waits.
  if (waiting.find("next attempt in") == std::string::npos) waiting = drive_error([&] { master->read(); });
  EXPECT_NE(waiting.find("not connected ("), std::string::npos) << waiting;
  EXPECT_NE(waiting.find("); next attempt in "), std::string::npos) << waiting;
  // The drive is back (a new one on the same port): the next call after 200 ms connects again,
  // and the master runs the CiA 402 sequence anew.
  RunningEmulator second(RunningEmulator::quiet(), port);
  std::this_thread::sleep_for(ModbusTcpDrive::kReconnectInterval + std::chrono::milliseconds(20));
  EXPECT_EQ(state_of(*master), PowerState::switch_on_disabled);
  EXPECT_TRUE(master->connected());
  enable(*master);
  const std::string statistics = master->take_exchange_statistics();
  EXPECT_NE(statistics.find(", 1 reconnect"), std::string::npos) << statistics;
  EXPECT_NE(statistics.find(" failed"), std::string::npos) << statistics;
}

// A raw connection to the emulator: sends bytes, reads an answer.
class RawConnection {
 public:
  explicit RawConnection(std::uint16_t port) : socket_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    timeval timeout{0, 500000};
    ::setsockopt(socket_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    connected_ = ::connect(socket_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  }
  ~RawConnection() { ::close(socket_); }
  bool connected() const { return connected_; }
  void send(const std::vector<std::uint8_t>& bytes) { ::send(socket_, bytes.data(), bytes.size(), MSG_NOSIGNAL); }
  // The answer's bytes; empty when the emulator closed the connection or sent nothing in 0.5 s.
  std::vector<std::uint8_t> receive() {
    std::vector<std::uint8_t> bytes(300);
    const ssize_t received = ::recv(socket_, bytes.data(), bytes.size(), 0);
    bytes.resize(received > 0 ? static_cast<std::size_t>(received) : 0);
    return bytes;
  }

 private:
  int socket_;
  bool connected_ = false;
};

TEST(ModbusLoopback, HostileFramesAreRefusedAndTheEmulatorServesOn) {
  RunningEmulator emulator;
  {
    RawConnection raw(emulator.port());
    ASSERT_TRUE(raw.connected());
    // An unknown function: exception 1. A read of 0 and of 126 registers: exception 3. A
    // write whose byte count lies: exception 3. A read across the map's gap: exception 2.
    raw.send({0, 1, 0, 0, 0, 2, 1, 0x2B});
    EXPECT_EQ(raw.receive(), (std::vector<std::uint8_t>{0, 1, 0, 0, 0, 3, 1, 0xAB, 1}));
    raw.send({0, 2, 0, 0, 0, 6, 1, 3, 0, 0, 0, 0});
    EXPECT_EQ(raw.receive(), (std::vector<std::uint8_t>{0, 2, 0, 0, 0, 3, 1, 0x83, 3}));
    raw.send({0, 3, 0, 0, 0, 6, 1, 3, 0, 0, 0, 126});
    EXPECT_EQ(raw.receive(), (std::vector<std::uint8_t>{0, 3, 0, 0, 0, 3, 1, 0x83, 3}));
    raw.send({0, 4, 0, 0, 0, 9, 1, 0x10, 0, 16, 0, 1, 4, 0, 6});
    EXPECT_EQ(raw.receive(), (std::vector<std::uint8_t>{0, 4, 0, 0, 0, 3, 1, 0x90, 3}));
    raw.send({0, 5, 0, 0, 0, 6, 1, 3, 0, 0, 0, 12});
    EXPECT_EQ(raw.receive(), (std::vector<std::uint8_t>{0, 5, 0, 0, 0, 3, 1, 0x83, 2}));
    // Not Modbus TCP at all: the connection is closed.
    raw.send({'G', 'E', 'T', ' ', '/', ' ', 'H', 'T', 'T', 'P', '/', '1', '.', '1', '\r', '\n'});
    EXPECT_TRUE(raw.receive().empty());
  }
  // Half a frame, then nothing: it stalls nothing, and the next master replaces it.
  RawConnection half(emulator.port());
  half.send({0, 1, 0, 0, 0, 6, 1, 3});
  const auto master = master_of(emulator.port());
  master->open();
  EXPECT_EQ(state_of(*master), PowerState::switch_on_disabled);
}

TEST(ModbusLoopback, AScatteredMapIsReadInOneRequestPerContiguousBlockInItsWordOrder) {
  // The statusword and error code apart from the position, velocity not placed, low word first.
  modbus::ModbusMap map = modbus::default_modbus_map();
  map.registers[static_cast<std::size_t>(modbus::DriveObject::velocity_actual)].reset();
  map.registers[static_cast<std::size_t>(modbus::DriveObject::error_code)]->address = 40;
  map.registers[static_cast<std::size_t>(modbus::DriveObject::position_actual)]->address = 100;
  map.high_word_first = false;
  DriveEmulatorSettings settings = RunningEmulator::quiet();
  settings.listen_host = "127.0.0.1";
  settings.listen_port = 0;
  settings.initial_position_m = -0.0123;
  DriveEmulator emulator(linear_servo_plant(), EmulatedDriveSettings{}, map, settings);
  std::atomic<bool> stop{false};
  std::thread server([&] { emulator.serve(stop); });
  modbus::ModbusTcpSpec spec;
  spec.host = "127.0.0.1";
  spec.port = emulator.port();
  ModbusTcpDrive master(spec, map);
  master.open();
  master.take_exchange_statistics();
  const DriveFeedback feedback = master.read();
  EXPECT_NEAR(feedback.position_m, -0.0123, 1e-9);
  EXPECT_FALSE(feedback.has_velocity);
  EXPECT_EQ(decode_statusword(feedback.statusword), PowerState::switch_on_disabled);
  const std::string statistics = master.take_exchange_statistics();
  EXPECT_NE(statistics.find(", 3 requests"), std::string::npos) << statistics;
  master.close();
  stop.store(true);
  server.join();
  EXPECT_NE(drive_error([&] { master.read(); }).find("read of input block 1 of 3 (register 0: statusword): "),
            std::string::npos);
}

TEST(ModbusLoopback, RoundTripsAreMeasured) {
  RunningEmulator emulator;
  const auto master = master_of(emulator.port());
  master->open();
  master->take_exchange_statistics();
  for (int i = 0; i < 1000; ++i) master->read();
  const std::string statistics = master->take_exchange_statistics();
  EXPECT_NE(statistics.find(", 1000 requests"), std::string::npos) << statistics;
  std::cout << "loopback, default map, one read per sample: " << statistics << "\n";
}

}  // namespace
}  // namespace netmc::drive
