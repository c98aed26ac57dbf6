#pragma once
// A CiA 402 drive behind Modbus TCP (--drive modbus-tcp:HOST:PORT[,unit=N][,map=FILE]
// [,timeout=DURATION]), with netmc as the master over libmodbus. The register map says where
// each object is and how its value scales; a cyclic read takes one request per contiguous block
// of what read() needs (one for the default map).
//
// Every answer is checked before it is believed: its transaction and protocol ids, its unit id
// (libmodbus 3.1.6 does not compare a TCP answer's unit with the request's), its function code,
// its length and, for a write, its echo. Every failure is a DriveError naming the operation, the
// object and its registers, and the cause: a Modbus exception by name, an answer from another
// unit, a timeout, a closed connection.
//
// A failure of the link (anything but a Modbus exception) closes the connection, so no late
// answer to one request is taken for the next. The next call connects again, at most once per
// 200 ms; the call that failed has thrown first, so a reconnect never passes unnoticed in a job.
//
// A job's cycle budget (set_cycle_budget: the job's period, at least 30 ms): the requests of one cycle, from the
// end of one read() to the end of the next (the setpoint's write and the feedback's read), wait
// for their answers at most the budget together. One that runs out fails as "drive exchange took
// 20.1 ms without an answer, over the 20 ms cycle budget" and closes the connection; the next
// request (the trip's quick stop) connects again at once, without the 200 ms pause, and is sent
// with what is left of the cycle's budget: one slow drive costs its node's other axes at most one
// budget per cycle.

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "server/drive/drive.hpp"
#include "server/drive/modbus/exchange_statistics.hpp"
#include "server/drive/modbus/modbus_map.hpp"
#include "server/drive/modbus/modbus_tcp_spec.hpp"

struct _modbus;  // libmodbus's context (modbus_t)

namespace netmc::drive::modbus {

class ModbusTcpDrive final : public Drive {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kReconnectInterval{200};
  static constexpr std::chrono::milliseconds kOpenConnectTimeout{1000};

  // `spec.unit` unset: the map's unit_id. Nothing connects here.
  ModbusTcpDrive(const ModbusTcpSpec& spec, ModbusMap map);
  // The text after `modbus-tcp:`; loads the map file it names. Throws std::invalid_argument.
  static std::unique_ptr<ModbusTcpDrive> from_spec(const std::string& text);
  ~ModbusTcpDrive() override;

  std::string describe() const override;  // "modbus-tcp:127.0.0.1:1502 unit 1"
  OperationMode job_mode() const override { return map_.job_mode; }
  AxisLimits configured_limits() const override { return map_.limits; }

  // Connects (within 1 s), then reads the input block: the statusword must decode to a CiA 402
  // state. Throws DriveError.
  void open() override;
  // Disable voltage (the power stage off) if connected, then disconnects; never throws.
  void close() noexcept override;

  void write_controlword(std::uint16_t word) override;
  void write_mode(OperationMode mode) override;
  void write_target(OperationMode mode, double value) override;
  DriveFeedback read() override;
  // Skipped when the map places no quick stop deceleration.
  void write_quick_stop_deceleration(double deceleration_m_s2) override;
  std::string take_exchange_statistics() override { return statistics_.take_summary("modbus"); }
  void set_cycle_budget(double budget_s) override;

  const ModbusMap& map() const { return map_; }
  bool connected() const { return context_ != nullptr; }

 private:
  // A run of registers read in one request.
  struct ReadBlock {
    std::uint16_t address = 0;
    std::uint16_t count = 0;
    std::string operation;  // "read of input block (registers 0-6: statusword, ...)"
  };
  struct ContextCloser {
    void operator()(_modbus* context) const;
  };

  void plan_reads();
  void connect(std::chrono::milliseconds connect_timeout, const std::string& operation);
  void disconnect() noexcept;
  // Connected, or connects if the last attempt is 200 ms old; throws DriveError otherwise.
  void ensure_connected(const std::string& operation);
  // Sends the request PDU (function code first) to the unit; the whole answer (MBAP header
  // first) is then in answer_, its length returned. Throws DriveError "OPERATION: CAUSE".
  std::size_t exchange(const std::uint8_t* pdu, std::size_t pdu_length, const std::string& operation);
  void read_registers(const ReadBlock& block, std::uint16_t* words);
  void write_object(DriveObject object, double value);
  [[noreturn]] void fail_link(const std::string& operation, const std::string& cause);
  // How long the next request may wait for its answer: the timeout, or what is left of the
  // cycle's budget when that is shorter.
  double wait_limit_s() const;

  std::string host_;
  std::uint16_t port_;
  std::uint8_t unit_;
  double timeout_s_;
  ModbusMap map_;
  std::unique_ptr<_modbus, ContextCloser> context_;
  Clock::time_point last_connect_attempt_{};
  bool attempted_ = false;
  std::string last_link_failure_;
  std::vector<ReadBlock> read_blocks_;
  std::array<std::string, kDriveObjectCount> write_operations_;  // "write of controlword (register 16)"
  std::array<std::uint16_t, 128> read_words_{};  // a read block's registers, from its first
  std::array<std::uint8_t, 260> answer_{};       // MODBUS_TCP_MAX_ADU_LENGTH
  ExchangeStatistics statistics_;
  double budget_s_ = 0.0;          // 0: none
  double cycle_waited_s_ = 0.0;    // waited for answers since the last read() ended
  bool reconnect_at_once_ = false;  // the last failure was the budget's, not the link's
  bool reconnected_at_once_ = false;  // this connection was such a reconnect
};

}  // namespace netmc::drive::modbus
