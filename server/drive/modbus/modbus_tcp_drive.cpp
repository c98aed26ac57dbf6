#include "server/drive/modbus/modbus_tcp_drive.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <modbus/modbus.h>
#include <netdb.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "server/drive/cia402.hpp"
#include "server/drive/modbus/duration_text.hpp"
#include "server/drive/modbus/modbus_exception_names.hpp"
#include "server/drive/modbus/modbus_map_file.hpp"

namespace netmc::drive::modbus {
namespace {

constexpr std::uint16_t kMaxReadRegisters = 125;  // the protocol's limit for one read
constexpr std::size_t kHeaderLength = 7;           // MBAP: transaction, protocol, length, unit

std::uint8_t high_byte(std::uint16_t value) { return static_cast<std::uint8_t>(value >> 8); }
std::uint8_t low_byte(std::uint16_t value) { return static_cast<std::uint8_t>(value & 0xFF); }

std::string registers_text(std::uint16_t address, std::uint16_t count) {
  if (count == 1) return fmt::format("register {}", address);
  return fmt::format("registers {}-{}", address, address + count - 1);
}

// The IPv4 address to connect to: the host itself, or what a name resolves to.
std::string resolve_ipv4(const std::string& host) {
  in_addr address{};
  if (inet_pton(AF_INET, host.c_str(), &address) == 1) return host;
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const int status = getaddrinfo(host.c_str(), nullptr, &hints, &found);
  if (status != 0 || found == nullptr) {
    throw std::runtime_error(fmt::format("cannot resolve '{}' ({})", host, gai_strerror(status)));
  }
  char text[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(found->ai_addr)->sin_addr, text, sizeof text);
  freeaddrinfo(found);
  return text;
}

void set_timeout(modbus_t* context, double seconds) {
  const auto whole = static_cast<std::uint32_t>(seconds);
  const auto micro = static_cast<std::uint32_t>(std::lround((seconds - whole) * 1e6));
  modbus_set_response_timeout(context, whole + micro / 1000000, micro % 1000000);
}

DriveObject target_of(OperationMode mode) {
  switch (mode) {
    case OperationMode::csp: return DriveObject::target_position;
    case OperationMode::csv: return DriveObject::target_velocity;
    case OperationMode::cst: return DriveObject::target_torque;
  }
  return DriveObject::target_torque;
}

}  // namespace

void ModbusTcpDrive::ContextCloser::operator()(_modbus* context) const {
  modbus_close(context);
  modbus_free(context);
}

ModbusTcpDrive::ModbusTcpDrive(const ModbusTcpSpec& spec, ModbusMap map)
    : host_(spec.host),
      port_(spec.port),
      unit_(spec.unit.value_or(map.unit_id)),
      timeout_s_(spec.timeout_s),
      map_(std::move(map)) {
  map_.validate();
  plan_reads();
  for (const auto& info : drive_objects()) {
    if (const auto& placement = map_.find(info.object)) {
      write_operations_[static_cast<std::size_t>(info.object)] =
          fmt::format("write of {} ({})", info.key, registers_text(placement->address, placement->count()));
    }
  }
}

std::unique_ptr<ModbusTcpDrive> ModbusTcpDrive::from_spec(const std::string& text) {
  const ModbusTcpSpec spec = parse_modbus_tcp_spec(text);
  ModbusMap map = spec.map_path ? load_modbus_map(*spec.map_path) : default_modbus_map();
  return std::make_unique<ModbusTcpDrive>(spec, std::move(map));
}

ModbusTcpDrive::~ModbusTcpDrive() { close(); }

std::string ModbusTcpDrive::describe() const { return fmt::format("modbus-tcp:{}:{} unit {}", host_, port_, unit_); }

// The objects read() needs, in as few requests as the map allows: neighbours share a request
// when every register between them belongs to the map (a drive may refuse to read a gap).
void ModbusTcpDrive::plan_reads() {
  std::vector<DriveObject> needed{DriveObject::statusword, DriveObject::error_code, DriveObject::position_actual};
  if (map_.has(DriveObject::velocity_actual)) needed.push_back(DriveObject::velocity_actual);
  std::sort(needed.begin(), needed.end(),
            [&](DriveObject a, DriveObject b) { return map_.at(a).address < map_.at(b).address; });
  for (const DriveObject object : needed) {
    const RegisterPlacement& placement = map_.at(object);
    const auto end = [](const ReadBlock& block) { return block.address + block.count; };
    bool joins = !read_blocks_.empty() && placement.address + placement.count() - read_blocks_.back().address <=
                                              kMaxReadRegisters;
    for (int address = joins ? end(read_blocks_.back()) : 0; joins && address < placement.address; ++address) {
      joins = map_.object_at(static_cast<std::uint16_t>(address)).has_value();
    }
    if (!joins) read_blocks_.push_back({placement.address, 0, {}});
    ReadBlock& block = read_blocks_.back();
    block.count = static_cast<std::uint16_t>(placement.address + placement.count() - block.address);
  }
  for (std::size_t i = 0; i < read_blocks_.size(); ++i) {
    ReadBlock& block = read_blocks_[i];
    std::string names;
    for (int address = block.address; address < block.address + block.count; ++address) {
      const auto slot = map_.object_at(static_cast<std::uint16_t>(address));
      if (slot && slot->second == 0) names += (names.empty() ? "" : ", ") + std::string(object_info(slot->first).key);
    }
    const std::string which = read_blocks_.size() == 1 ? "" : fmt::format(" {} of {}", i + 1, read_blocks_.size());
    block.operation =
        fmt::format("read of input block{} ({}: {})", which, registers_text(block.address, block.count), names);
  }
}

void ModbusTcpDrive::connect(std::chrono::milliseconds connect_timeout, const std::string& operation) {
  disconnect();
  reconnected_at_once_ = false;
  last_connect_attempt_ = Clock::now();
  attempted_ = true;
  const std::string where = fmt::format("connect to {}:{}", host_, port_);
  std::string address;
  try {
    address = resolve_ipv4(host_);
  } catch (const std::runtime_error& error) {
    last_link_failure_ = where + ": " + error.what();
    throw DriveError(operation + ": " + last_link_failure_);
  }
  std::unique_ptr<_modbus, ContextCloser> context(modbus_new_tcp(address.c_str(), port_));
  if (!context) {
    last_link_failure_ = where + ": " + modbus_strerror(errno);
    throw DriveError(operation + ": " + last_link_failure_);
  }
  // libmodbus bounds its connect by the response timeout.
  set_timeout(context.get(), std::chrono::duration<double>(connect_timeout).count());
  if (modbus_connect(context.get()) == -1) {
    const int error = errno;
    // A connect that ran out of time leaves errno as the non-blocking connect set it.
    const std::string cause = error == EINPROGRESS || error == ETIMEDOUT
                                  ? "no answer within " + format_duration(std::chrono::duration<double>(connect_timeout).count())
                              : error == ECONNREFUSED ? std::string("connection refused")
                                                      : std::string(std::strerror(error));
    last_link_failure_ = where + ": " + cause;
    throw DriveError(operation + ": " + last_link_failure_);
  }
  set_timeout(context.get(), timeout_s_);
  // No separate limit between bytes: the whole answer must come within the response timeout.
  modbus_set_byte_timeout(context.get(), 0, 0);
  context_ = std::move(context);
}

void ModbusTcpDrive::disconnect() noexcept { context_.reset(); }

void ModbusTcpDrive::set_cycle_budget(double budget_s) {
  budget_s_ = budget_s > 0.0 && std::isfinite(budget_s) ? budget_s : 0.0;
  cycle_waited_s_ = 0.0;
}

double ModbusTcpDrive::wait_limit_s() const {
  if (budget_s_ <= 0.0) return timeout_s_;
  // At least 100 us: libmodbus takes no zero timeout, and a request past the budget still leaves.
  return std::max(1e-4, std::min(timeout_s_, budget_s_ - cycle_waited_s_));
}

void ModbusTcpDrive::ensure_connected(const std::string& operation) {
  if (context_) return;
  if (!attempted_) throw DriveError(operation + ": the drive is not open");
  const auto since = Clock::now() - last_connect_attempt_;
  const bool at_once = std::exchange(reconnect_at_once_, false);
  if (since < kReconnectInterval && !at_once) {
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(kReconnectInterval - since).count();
    statistics_.record_failure();
    throw DriveError(fmt::format("{}: not connected ({}); next attempt in {} ms", operation, last_link_failure_, wait));
  }
  if (!at_once) cycle_waited_s_ = 0.0;  // a cycle of its own
  // Within the cycle's budget too (whole milliseconds, at least one).
  const auto connect_timeout = std::max(std::chrono::milliseconds(1),
                                        std::chrono::ceil<std::chrono::milliseconds>(
                                            std::chrono::duration<double>(wait_limit_s())));
  try {
    connect(connect_timeout, operation);
  } catch (const DriveError&) {
    statistics_.record_failure();
    throw;
  }
  statistics_.record_reconnect();
  reconnected_at_once_ = at_once;
}

void ModbusTcpDrive::fail_link(const std::string& operation, const std::string& cause) {
  last_link_failure_ = cause;
  disconnect();
  statistics_.record_failure();
  throw DriveError(operation + ": " + cause);
}

std::size_t ModbusTcpDrive::exchange(const std::uint8_t* pdu, std::size_t pdu_length, const std::string& operation) {
  ensure_connected(operation);
  std::array<std::uint8_t, 254> request{};  // unit + PDU (at most 253 bytes)
  request[0] = unit_;
  std::copy(pdu, pdu + pdu_length, request.begin() + 1);
  const double limit_s = wait_limit_s();
  set_timeout(context_.get(), limit_s);
  const auto start = Clock::now();
  // A raw request: libmodbus frames it (transaction id 0) and hands back the whole answer, which
  // is checked here, its unit id included.
  if (modbus_send_raw_request(context_.get(), request.data(), static_cast<int>(pdu_length + 1)) == -1) {
    fail_link(operation, std::string("sending failed: ") + modbus_strerror(errno));
  }
  const int length = modbus_receive_confirmation(context_.get(), answer_.data());
  const double waited_s = std::chrono::duration<double>(Clock::now() - start).count();
  cycle_waited_s_ += waited_s;
  if (length == -1) {
    const int error = errno;
    if (error == ETIMEDOUT && limit_s < timeout_s_) {
      // The drive is slow, the link may be sound: the trip's quick stop goes out at once (once:
      // after that, reconnects wait their 200 ms as after any failure).
      reconnect_at_once_ = !reconnected_at_once_;
      fail_link(operation, fmt::format("drive exchange took {} without an answer, over the {} cycle budget",
                                       format_duration(cycle_waited_s_), format_duration(budget_s_)));
    }
    if (error == ETIMEDOUT) fail_link(operation, "timeout after " + format_duration(timeout_s_));
    if (error == ECONNRESET) fail_link(operation, "connection closed by the drive");
    if (error == EMBBADDATA) fail_link(operation, "malformed answer (more data than its function allows)");
    fail_link(operation, modbus_strerror(error));
  }
  statistics_.record(std::chrono::duration<double>(Clock::now() - start).count());
  const auto size = static_cast<std::size_t>(length);
  if (size < kHeaderLength + 2) fail_link(operation, fmt::format("answer of {} bytes, too short", size));
  if (answer_[0] != 0 || answer_[1] != 0 || answer_[2] != 0 || answer_[3] != 0) {
    fail_link(operation, fmt::format("answer with transaction id {} and protocol id {} (expected 0 and 0)",
                                     answer_[0] << 8 | answer_[1], answer_[2] << 8 | answer_[3]));
  }
  if (answer_[6] != unit_) fail_link(operation, fmt::format("answer from unit {} (asked unit {})", answer_[6], unit_));
  const std::uint8_t function = answer_[kHeaderLength];
  if (function == (pdu[0] | 0x80)) {
    // The drive refused the request: the link itself is fine.
    throw DriveError(operation + ": " + describe_modbus_exception(answer_[kHeaderLength + 1]));
  }
  if (function != pdu[0]) {
    fail_link(operation, fmt::format("answer with function 0x{:02X} to function 0x{:02X}", function, pdu[0]));
  }
  return size;
}

void ModbusTcpDrive::read_registers(const ReadBlock& block, std::uint16_t* words) {
  const std::uint8_t pdu[] = {MODBUS_FC_READ_HOLDING_REGISTERS, high_byte(block.address), low_byte(block.address),
                              high_byte(block.count), low_byte(block.count)};
  const std::size_t length = exchange(pdu, sizeof pdu, block.operation);
  const std::size_t bytes = 2u * block.count;
  if (answer_[kHeaderLength + 1] != bytes || length != kHeaderLength + 2 + bytes) {
    fail_link(block.operation, fmt::format("answer with {} data bytes for {} registers", answer_[kHeaderLength + 1],
                                           block.count));
  }
  for (std::size_t i = 0; i < block.count; ++i) {
    words[i] = static_cast<std::uint16_t>(answer_[kHeaderLength + 2 + 2 * i] << 8 | answer_[kHeaderLength + 3 + 2 * i]);
  }
}

void ModbusTcpDrive::write_object(DriveObject object, double value) {
  const std::string& operation = write_operations_[static_cast<std::size_t>(object)];
  const RegisterPlacement& placement = map_.at(object);
  std::array<std::uint16_t, 2> words{};
  std::uint16_t count = 0;
  try {
    count = map_.to_words(object, value, words);
  } catch (const std::out_of_range& error) {
    // The map's text begins with the object's name, which the operation names already.
    const std::string text = error.what();
    const std::size_t colon = text.find(": ");
    throw DriveError(operation + ": " + (colon == std::string::npos ? text : text.substr(colon + 2)));
  }
  if (count == 1) {
    const std::uint8_t pdu[] = {MODBUS_FC_WRITE_SINGLE_REGISTER, high_byte(placement.address),
                                low_byte(placement.address), high_byte(words[0]), low_byte(words[0])};
    const std::size_t length = exchange(pdu, sizeof pdu, operation);
    if (length != kHeaderLength + sizeof pdu || !std::equal(pdu, pdu + sizeof pdu, answer_.begin() + kHeaderLength)) {
      fail_link(operation, "answer does not echo the write");
    }
    return;
  }
  const std::uint8_t pdu[] = {MODBUS_FC_WRITE_MULTIPLE_REGISTERS,
                              high_byte(placement.address),
                              low_byte(placement.address),
                              0,
                              2,
                              4,
                              high_byte(words[0]),
                              low_byte(words[0]),
                              high_byte(words[1]),
                              low_byte(words[1])};
  const std::size_t length = exchange(pdu, sizeof pdu, operation);
  if (length != kHeaderLength + 5 || !std::equal(pdu, pdu + 5, answer_.begin() + kHeaderLength)) {
    fail_link(operation, "answer does not echo the write's address and count");
  }
}

void ModbusTcpDrive::open() {
  connect(kOpenConnectTimeout, "open");
  const DriveFeedback feedback = read();
  if (!decode_statusword(feedback.statusword)) {
    const RegisterPlacement& placement = map_.at(DriveObject::statusword);
    disconnect();
    throw DriveError(fmt::format("open: statusword ({}) reads 0x{:04X}, which is no CiA 402 state",
                                 registers_text(placement.address, 1), feedback.statusword));
  }
}

void ModbusTcpDrive::close() noexcept {
  if (context_) {
    try {
      write_object(DriveObject::controlword, controlword::disable_voltage);
    } catch (...) {
      // Closing anyway: the drive's own watchdog stops an axis whose master is gone.
    }
  }
  disconnect();
  attempted_ = false;  // no reconnect until the next open()
}

void ModbusTcpDrive::write_controlword(std::uint16_t word) { write_object(DriveObject::controlword, word); }

void ModbusTcpDrive::write_mode(OperationMode mode) {
  write_object(DriveObject::modes_of_operation, static_cast<double>(static_cast<int>(mode)));
}

void ModbusTcpDrive::write_target(OperationMode mode, double value) {
  write_object(target_of(mode), value);
}

void ModbusTcpDrive::write_quick_stop_deceleration(double deceleration_m_s2) {
  if (!map_.has(DriveObject::quick_stop_deceleration)) return;
  write_object(DriveObject::quick_stop_deceleration, deceleration_m_s2);
}

DriveFeedback ModbusTcpDrive::read() {
  DriveFeedback feedback;
  feedback.has_velocity = map_.has(DriveObject::velocity_actual);
  for (const ReadBlock& block : read_blocks_) {
    read_registers(block, read_words_.data());
    const auto take = [&](DriveObject object, auto assign) {
      const auto& placement = map_.find(object);
      if (placement && placement->address >= block.address &&
          placement->address + placement->count() <= block.address + block.count) {
        assign(map_.from_words(object, read_words_.data() + (placement->address - block.address)));
      }
    };
    take(DriveObject::statusword, [&](double v) { feedback.statusword = static_cast<std::uint16_t>(v); });
    take(DriveObject::error_code, [&](double v) { feedback.error_code = static_cast<std::uint16_t>(v); });
    take(DriveObject::position_actual, [&](double v) { feedback.position_m = v; });
    take(DriveObject::velocity_actual, [&](double v) { feedback.velocity_m_s = v; });
  }
  cycle_waited_s_ = 0.0;  // the cycle's exchange is complete
  return feedback;
}

}  // namespace netmc::drive::modbus
