#include "server/drive/emulator/drive_emulator.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "server/drive/cia402.hpp"
#include "server/drive/modbus/duration_text.hpp"
#include "server/drive/modbus/modbus_exception_names.hpp"

namespace netmc::drive::emulator {
namespace {

constexpr std::size_t kHeaderLength = 7;  // MBAP: transaction, protocol, length, unit

std::uint16_t word_at(const std::uint8_t* bytes) { return static_cast<std::uint16_t>(bytes[0] << 8 | bytes[1]); }

std::string peer_name(int socket) {
  sockaddr_in peer{};
  socklen_t length = sizeof peer;
  if (getpeername(socket, reinterpret_cast<sockaddr*>(&peer), &length) != 0 || peer.sin_family != AF_INET) {
    return "?";
  }
  char text[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &peer.sin_addr, text, sizeof text);
  return fmt::format("{}:{}", text, ntohs(peer.sin_port));
}

// Why libmodbus could not send an answer: a send that took part of it means the socket's buffer
// is full, the master not reading its answers.
std::string send_failure(int error) {
  if (error == EMBBADDATA) return "answer not sent: the master does not read its answers";
  return std::string("answer not sent: ") + modbus_strerror(error);
}

void set_non_blocking(int socket) { fcntl(socket, F_SETFL, fcntl(socket, F_GETFL) | O_NONBLOCK); }

// The drive at rest where the axis starts, initialised (Switch on disabled).
EmulatedDrive ready_drive(std::unique_ptr<plant::AxisPlant> plant, const EmulatedDriveSettings& settings,
                          double position_m) {
  if (!std::isfinite(position_m)) throw std::invalid_argument("--initial-position: expected a finite position in metres");
  EmulatedDrive drive(std::move(plant), settings);
  drive.restart_at(position_m);
  drive.power_up();
  return drive;
}

}  // namespace

DriveEmulator::DriveEmulator(std::unique_ptr<plant::AxisPlant> plant, EmulatedDriveSettings drive_settings,
                             modbus::ModbusMap map, DriveEmulatorSettings settings)
    : map_(std::move(map)),
      drive_(ready_drive(std::move(plant), drive_settings, settings.initial_position_m)),
      registers_(map_, drive_),
      settings_(std::move(settings)),
      unit_(settings_.unit.value_or(map_.unit_id)),
      start_(Clock::now()),
      logged_state_(PowerState::not_ready_to_switch_on) {
  map_.validate();
  if (!(settings_.watchdog_s >= 0.0) || !std::isfinite(settings_.watchdog_s)) {
    throw std::invalid_argument("--watchdog: expected a duration, 0 for none");
  }
  in_addr address{};
  if (inet_pton(AF_INET, settings_.listen_host.c_str(), &address) != 1) {
    throw std::invalid_argument("--listen: expected an IPv4 address for HOST, got '" + settings_.listen_host.substr(0, 64) +
                                "'");
  }
  logged_state_ = drive_.state();
  actual_position_m_.store(drive_.position());

  // The image libmodbus answers from covers the map's registers, first to last.
  std::uint32_t first = 65535, last = 0;
  for (const auto& info : modbus::drive_objects()) {
    if (const auto& placement = map_.find(info.object)) {
      first = std::min<std::uint32_t>(first, placement->address);
      last = std::max<std::uint32_t>(last, placement->address + placement->count() - 1u);
    }
  }
  image_start_ = static_cast<std::uint16_t>(first);
  image_ = modbus_mapping_new_start_address(0, 0, 0, 0, first, last - first + 1, 0, 0);
  context_ = modbus_new_tcp(settings_.listen_host.c_str(), settings_.listen_port);
  if (image_ == nullptr || context_ == nullptr) {
    if (image_) modbus_mapping_free(image_);
    if (context_) modbus_free(context_);
    throw std::runtime_error(std::string("modbus: ") + modbus_strerror(errno));
  }
  // libmodbus sleeps for the response timeout before some exception answers (requests it finds
  // malformed); every request is checked before it reaches libmodbus, and this keeps any such
  // sleep at a microsecond.
  modbus_set_response_timeout(context_, 0, 1);
  listen_socket_ = modbus_tcp_listen(context_, 1);
  if (listen_socket_ == -1) {
    const std::string cause = std::strerror(errno);
    modbus_mapping_free(image_);
    modbus_free(context_);
    throw std::runtime_error(fmt::format("--listen {}:{}: cannot listen ({})", settings_.listen_host,
                                         settings_.listen_port, cause));
  }
  set_non_blocking(listen_socket_);
  fcntl(listen_socket_, F_SETFD, FD_CLOEXEC);
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  getsockname(listen_socket_, reinterpret_cast<sockaddr*>(&bound), &length);
  port_ = ntohs(bound.sin_port);
}

DriveEmulator::~DriveEmulator() {
  if (master_socket_ >= 0) ::close(master_socket_);
  if (listen_socket_ >= 0) ::close(listen_socket_);
  modbus_set_socket(context_, -1);
  modbus_mapping_free(image_);
  modbus_free(context_);
}

std::string DriveEmulator::address() const { return fmt::format("{}:{}", settings_.listen_host, port_); }

void DriveEmulator::advance(double now) {
  if (settings_.watchdog_s > 0.0 && drive_.state() == PowerState::operation_enabled &&
      now - last_request_s_ > settings_.watchdog_s) {
    drive_.advance_to(last_request_s_ + settings_.watchdog_s);
    if (drive_.state() == PowerState::operation_enabled) {
      drive_.raise_fault(error_code::communication);
      spdlog::warn("watchdog: no request for {} in Operation enabled: fault {}",
                   modbus::format_duration(settings_.watchdog_s), describe_error_code(error_code::communication));
    }
  }
  drive_.advance_to(now);
  drive_.check_model();
  actual_position_m_.store(drive_.position());
  log_state_change();
}

void DriveEmulator::log_state_change() {
  if (drive_.state() == logged_state_) return;
  const PowerState before = logged_state_;
  logged_state_ = drive_.state();
  spdlog::info("{} -> {} (error {}, at {:.6f} m)", power_state_name(before), power_state_name(logged_state_),
               describe_error_code(drive_.error_code()), drive_.position());
}

void DriveEmulator::serve(const std::atomic<bool>& stop) {
  const double cycle_s = drive_.settings().cycle_s;
  double next_tick = now_s();
  while (!stop.load()) {
    double now = now_s();
    if (now >= next_tick) {
      advance(now);
      next_tick += cycle_s;
      if (next_tick <= now) next_tick = now + cycle_s;  // a late tick: no burst to catch up
    }
    pollfd sockets[2] = {{listen_socket_, POLLIN, 0}, {master_socket_, POLLIN, 0}};
    const nfds_t count = master_socket_ >= 0 ? 2 : 1;
    const double wait_s = std::max(0.0, next_tick - now_s());
    timespec timeout{static_cast<time_t>(wait_s), static_cast<long>((wait_s - std::floor(wait_s)) * 1e9)};
    const int ready = ppoll(sockets, count, &timeout, nullptr);
    if (ready < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
    }
    if (count == 2 && sockets[1].revents != 0) read_master();
    if (sockets[0].revents & POLLIN) accept_master();
  }
  if (master_socket_ >= 0) close_master("stopping");
  spdlog::info("stopped after {} requests ({} refused)", requests_, refusals_);
}

void DriveEmulator::accept_master() {
  const int socket = modbus_tcp_accept(context_, &listen_socket_);
  if (socket < 0) {
    // Gone before it was taken. libmodbus set its socket to -1: the master's stays.
    modbus_set_socket(context_, master_socket_);
    return;
  }
  set_non_blocking(socket);
  const int on = 1;
  setsockopt(socket, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  const std::string name = peer_name(socket);
  if (master_socket_ >= 0) {
    spdlog::warn("master {} connected: it replaces master {}", name, master_name_);
    ::close(master_socket_);
  } else {
    spdlog::info("master {} connected", name);
  }
  master_socket_ = socket;
  master_name_ = name;
  buffered_ = 0;
  modbus_set_socket(context_, master_socket_);
  if (!first_connection_s_) first_connection_s_ = now_s();
}

void DriveEmulator::close_master(const std::string& why) {
  spdlog::info("master {}: {}; connection closed", master_name_, why);
  ::close(master_socket_);
  master_socket_ = -1;
  buffered_ = 0;
  modbus_set_socket(context_, -1);
}

// One receive per wake-up: a master that sends without pause cannot starve the drive's ticks.
// After handle_frames less than one whole frame is left, so there is always room to receive.
void DriveEmulator::read_master() {
  ssize_t received = 0;
  do {
    received = recv(master_socket_, buffer_.data() + buffered_, buffer_.size() - buffered_, MSG_DONTWAIT);
  } while (received < 0 && errno == EINTR);
  if (received == 0) {
    close_master("disconnected");
    return;
  }
  if (received < 0) {
    if (errno != EAGAIN && errno != EWOULDBLOCK) close_master(std::string("receive failed: ") + std::strerror(errno));
    return;
  }
  buffered_ += static_cast<std::size_t>(received);
  handle_frames();
}

void DriveEmulator::handle_frames() {
  while (buffered_ >= kHeaderLength) {
    const std::uint16_t protocol = word_at(&buffer_[2]);
    const std::uint16_t length = word_at(&buffer_[4]);  // unit and PDU
    if (protocol != 0 || length < 2 || length > 254) {
      close_master(fmt::format("not Modbus TCP (protocol id {}, length {})", protocol, length));
      return;
    }
    const std::size_t size = 6u + length;
    if (buffered_ < size) break;
    handle_request(buffer_.data(), size);
    if (master_socket_ < 0) return;
    std::memmove(buffer_.data(), buffer_.data() + size, buffered_ - size);
    buffered_ -= size;
  }
}

void DriveEmulator::reply(const std::uint8_t* frame, std::size_t size) {
  if (modbus_reply(context_, frame, static_cast<int>(size), image_) == -1) {
    close_master(send_failure(errno));
  }
}

void DriveEmulator::reply_exception(const std::uint8_t* frame, std::uint8_t code, const std::string& why) {
  ++refusals_;
  const double now = now_s();
  if (now - refusal_logged_s_ >= 1.0 || refusal_logged_s_ < 0.0) {
    const std::string unlogged =
        refusals_unlogged_ > 0 ? fmt::format(" ({} more refused in the last second)", refusals_unlogged_) : "";
    spdlog::warn("master {}: function 0x{:02X} refused with {}: {}{}", master_name_, frame[kHeaderLength],
                 modbus::describe_modbus_exception(code), why, unlogged);
    refusal_logged_s_ = now;
    refusals_unlogged_ = 0;
  } else {
    ++refusals_unlogged_;
  }
  if (modbus_reply_exception(context_, frame, code) == -1) {
    close_master(send_failure(errno));
  }
}

void DriveEmulator::freeze_feedback(std::uint16_t address, std::uint16_t count, std::uint16_t* words) {
  if (frozen_words_.empty()) {
    for (const auto object : {modbus::DriveObject::position_actual, modbus::DriveObject::velocity_actual}) {
      const auto& placement = map_.find(object);
      if (!placement) continue;
      std::array<std::uint16_t, 2> now{};
      registers_.read(placement->address, placement->count(), now.data());
      for (std::uint16_t i = 0; i < placement->count(); ++i) {
        frozen_words_.emplace_back(static_cast<std::uint16_t>(placement->address + i), now[i]);
      }
    }
  }
  for (const auto& [register_address, word] : frozen_words_) {
    if (register_address >= address && register_address < address + count) words[register_address - address] = word;
  }
}

void DriveEmulator::handle_request(std::uint8_t* frame, std::size_t size) {
  ++requests_;
  const double arrived = now_s();
  const bool failing =
      settings_.fault && first_connection_s_ && arrived >= *first_connection_s_ + settings_.fault->after_s;
  if (failing && settings_.fault->kind == InjectedFault::Kind::slow) {
    // A drive that takes this long to answer: the request is served, and answered, only then.
    // Its arrival feeds the watchdog (the drive heard its master).
    advance(arrived);
    if (frame[kHeaderLength - 1] == unit_) last_request_s_ = arrived;
    std::this_thread::sleep_for(std::chrono::duration<double>(settings_.fault->delay_s));
  }
  const double now = now_s();
  advance(now);
  const std::uint8_t unit = frame[kHeaderLength - 1];
  if (failing) {
    if (!fault_announced_) {
      spdlog::warn("injected fault from now on: {}", settings_.fault->describe());
      fault_announced_ = true;
    }
    if (settings_.fault->kind == InjectedFault::Kind::silence) return;
    if (settings_.fault->kind == InjectedFault::Kind::exception) {
      ++refusals_;
      if (modbus_reply_exception(context_, frame, kServerDeviceFailure) == -1) {
        close_master(send_failure(errno));
      }
      return;
    }
  }
  if (unit != unit_) {
    reply_exception(frame, kGatewayTargetFailed, fmt::format("unit {} asked, this drive is unit {}", unit, unit_));
    return;
  }
  last_request_s_ = now;  // the watchdog is fed by requests for this drive
  // The wrong-unit fault: served, but answered for another unit.
  if (failing && settings_.fault->kind == InjectedFault::Kind::wrong_unit) {
    frame[kHeaderLength - 1] = static_cast<std::uint8_t>(unit_ + 1);
  }
  const std::uint8_t function = frame[kHeaderLength];
  const std::uint8_t* pdu = frame + kHeaderLength;
  const std::size_t pdu_size = size - kHeaderLength;
  switch (function) {
    case MODBUS_FC_READ_HOLDING_REGISTERS: {
      if (pdu_size != 5) return reply_exception(frame, kIllegalDataValue, "read request of the wrong length");
      const std::uint16_t address = word_at(pdu + 1), count = word_at(pdu + 3);
      if (count < 1 || count > MODBUS_MAX_READ_REGISTERS) {
        return reply_exception(frame, kIllegalDataValue, fmt::format("read of {} registers (1..125)", count));
      }
      if (std::uint32_t{address} + count > 65536u) {
        return reply_exception(frame, kIllegalDataAddress, "read past register 65535");
      }
      std::array<std::uint16_t, MODBUS_MAX_READ_REGISTERS> words{};
      const RegisterAccess access = registers_.read(address, count, words.data());
      if (!access.ok()) return reply_exception(frame, access.exception, access.why);
      if (failing && settings_.fault->kind == InjectedFault::Kind::frozen) freeze_feedback(address, count, words.data());
      std::copy(words.begin(), words.begin() + count, image_->tab_registers + (address - image_start_));
      return reply(frame, size);
    }
    case MODBUS_FC_WRITE_SINGLE_REGISTER: {
      if (pdu_size != 5) return reply_exception(frame, kIllegalDataValue, "write request of the wrong length");
      const std::uint16_t value = word_at(pdu + 3);
      const RegisterAccess access = registers_.write(word_at(pdu + 1), &value, 1);
      if (!access.ok()) return reply_exception(frame, access.exception, access.why);
      log_state_change();
      return reply(frame, size);
    }
    case MODBUS_FC_WRITE_MULTIPLE_REGISTERS: {
      const std::uint16_t address = pdu_size >= 6 ? word_at(pdu + 1) : 0, count = pdu_size >= 6 ? word_at(pdu + 3) : 0;
      if (pdu_size < 6 || count < 1 || count > MODBUS_MAX_WRITE_REGISTERS || pdu[5] != 2u * count ||
          pdu_size != 6u + 2u * count) {
        return reply_exception(frame, kIllegalDataValue, "write request of the wrong length or count");
      }
      if (std::uint32_t{address} + count > 65536u) {
        return reply_exception(frame, kIllegalDataAddress, "write past register 65535");
      }
      std::array<std::uint16_t, MODBUS_MAX_WRITE_REGISTERS> words{};
      for (std::size_t i = 0; i < count; ++i) words[i] = word_at(pdu + 6 + 2 * i);
      const RegisterAccess access = registers_.write(address, words.data(), count);
      if (!access.ok()) return reply_exception(frame, access.exception, access.why);
      log_state_change();
      return reply(frame, size);
    }
    default:
      return reply_exception(frame, kIllegalFunction, fmt::format("function 0x{:02X} is not served", function));
  }
}

}  // namespace netmc::drive::emulator
