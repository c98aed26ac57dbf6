#include "server/drive/plugin/plugin_drive.hpp"

#include <dlfcn.h>
#include <fmt/format.h>
#include <netmc/drive_plugin.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "server/drive/plugin/plugin_spec.hpp"
#include "server/drive/plugin/plugin_text.hpp"

namespace netmc::drive {
namespace {

// One error buffer per call, zeroed: a plugin that fails without a word leaves it empty.
struct ErrorBuffer {
  char text[NETMC_DRIVE_PLUGIN_ERROR_SIZE] = {};
  std::string str() const { return plugin_text(text, sizeof text, "(the plugin gave no reason)"); }
};

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw std::invalid_argument(fmt::format("plugin {}: {}", path, why));
}

// The file as the operator named it, checked before the dynamic loader sees it (its own
// messages do not say which of missing, unreadable or not an object it was).
void check_file(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) refuse(path, fmt::format("cannot read it: {}", std::strerror(errno)));
  if (!S_ISREG(status.st_mode)) refuse(path, "not a regular file");
  if (::access(path.c_str(), R_OK) != 0) refuse(path, fmt::format("cannot read it: {}", std::strerror(errno)));
}

// The table's functions by name, for the null check.
std::vector<std::pair<const char*, bool>> missing_functions(const netmc_drive_plugin_table& t) {
  return {
      {"create", t.create == nullptr},
      {"destroy", t.destroy == nullptr},
      {"describe", t.describe == nullptr},
      {"job_mode", t.job_mode == nullptr},
      {"supported_modes", t.supported_modes == nullptr},
      {"open", t.open == nullptr},
      {"close", t.close == nullptr},
      {"write_controlword", t.write_controlword == nullptr},
      {"write_mode", t.write_mode == nullptr},
      {"write_target", t.write_target == nullptr},
      {"read", t.read == nullptr},
      {"cycle", t.cycle == nullptr},
      {"write_quick_stop_deceleration", t.write_quick_stop_deceleration == nullptr},
  };
}

constexpr OperationMode kModes[] = {OperationMode::csp, OperationMode::csv, OperationMode::cst};

std::string mode_names(std::uint32_t modes) {
  std::string names;
  for (const OperationMode mode : kModes) {
    if (modes & NETMC_DRIVE_MODE_BIT(static_cast<int>(mode)))
      names += (names.empty() ? "" : ", ") + std::string(operation_mode_name(mode));
  }
  return names.empty() ? "none" : names;
}

}  // namespace

void PluginDrive::LibraryCloser::operator()(void* library) const { ::dlclose(library); }

std::unique_ptr<PluginDrive> PluginDrive::load(const std::string& text) {
  const PluginSpec spec = parse_plugin_spec(text);
  const std::string& path = spec.path;
  check_file(path);

  // A bare name would send dlopen searching the library path: load the file that was checked.
  const std::string load_path = path.find('/') == std::string::npos ? "./" + path : path;
  Library library(::dlopen(load_path.c_str(), RTLD_NOW | RTLD_LOCAL));
  if (!library) {
    const char* why = ::dlerror();
    refuse(path, fmt::format("cannot load it as a shared object: {}",
                             why ? plugin_text(why, std::strlen(why), "dlopen failed") : "dlopen failed"));
  }
  ::dlerror();
  const auto* table = static_cast<const netmc_drive_plugin_table*>(::dlsym(library.get(), NETMC_DRIVE_PLUGIN_ENTRY));
  if (table == nullptr) {
    refuse(path, "exports no " NETMC_DRIVE_PLUGIN_ENTRY " (the entry object <netmc/drive_plugin.h> declares)");
  }
  // The two fields every ABI version keeps first, before anything else of the table is trusted.
  if (table->abi_version != NETMC_DRIVE_PLUGIN_ABI_VERSION) {
    throw std::invalid_argument(
        fmt::format("plugin {} was built for drive plugin ABI {}; this netmc-axis speaks ABI {}", path,
                    table->abi_version, NETMC_DRIVE_PLUGIN_ABI_VERSION));
  }
  if (table->table_size != sizeof(netmc_drive_plugin_table)) {
    refuse(path, fmt::format("its function table has {} bytes; drive plugin ABI {} has {} (built with another "
                             "<netmc/drive_plugin.h>?)",
                             table->table_size, NETMC_DRIVE_PLUGIN_ABI_VERSION, sizeof(netmc_drive_plugin_table)));
  }
  for (const auto& [name, missing] : missing_functions(*table)) {
    if (missing) refuse(path, fmt::format("its function table has no {} (a null pointer)", name));
  }

  std::vector<netmc_drive_setting> settings;
  settings.reserve(spec.settings.size());
  for (const auto& [key, value] : spec.settings) settings.push_back({key.c_str(), value.c_str()});
  netmc_drive* drive = nullptr;
  ErrorBuffer error;
  if (table->create(settings.data(), settings.size(), &drive, error.text, sizeof error.text) != NETMC_DRIVE_OK) {
    refuse(path, fmt::format("refused its configuration: {}", error.str()));
  }
  if (drive == nullptr) refuse(path, "create reported success but gave no drive");
  std::unique_ptr<PluginDrive> loaded(new PluginDrive(std::move(library), table, drive, path));
  loaded->query_modes();
  loaded->refresh_description();
  return loaded;
}

PluginDrive::PluginDrive(Library library, const netmc_drive_plugin_table* table, netmc_drive* drive, std::string path)
    : library_(std::move(library)), table_(table), drive_(drive), path_(std::move(path)) {}

PluginDrive::~PluginDrive() {
  close();
  table_->destroy(drive_);
}

void PluginDrive::query_modes() {
  ErrorBuffer error;
  if (table_->supported_modes(drive_, &modes_, error.text, sizeof error.text) != NETMC_DRIVE_OK) {
    refuse(path_, fmt::format("supported_modes: {}", error.str()));
  }
  constexpr std::uint32_t kKnown = NETMC_DRIVE_MODE_BIT(NETMC_DRIVE_MODE_CSP) |
                                   NETMC_DRIVE_MODE_BIT(NETMC_DRIVE_MODE_CSV) |
                                   NETMC_DRIVE_MODE_BIT(NETMC_DRIVE_MODE_CST);
  if (modes_ == 0 || (modes_ & ~kKnown) != 0) {
    refuse(path_, fmt::format("supported_modes gave 0x{:X}: it must name CSP, CSV or CST only "
                              "(NETMC_DRIVE_MODE_BIT of 8, 9, 10)",
                              modes_));
  }
  std::int8_t code = 0;
  if (table_->job_mode(drive_, &code, error.text, sizeof error.text) != NETMC_DRIVE_OK) {
    refuse(path_, fmt::format("job_mode: {}", error.str()));
  }
  const auto mode = operation_mode_from_code(code);
  if (!mode || !supports(*mode)) {
    refuse(path_, fmt::format("its job mode {} is not one of the modes it supports ({})", code, mode_names(modes_)));
  }
  job_mode_ = *mode;
}

bool PluginDrive::supports(OperationMode mode) const {
  return (modes_ & NETMC_DRIVE_MODE_BIT(static_cast<int>(mode))) != 0;
}

void PluginDrive::require_mode(OperationMode mode, const char* call) const {
  if (!supports(mode)) {
    throw DriveError(fmt::format("plugin {}: {} in {}: the plugin supports {} only", path_, call, operation_mode_name(mode),
                                 mode_names(modes_)));
  }
}

void PluginDrive::check(int status, const char* call, const char* error) const {
  if (status == NETMC_DRIVE_OK) return;
  throw DriveError(fmt::format("plugin {}: {}: {}", path_, call,
                               plugin_text(error, NETMC_DRIVE_PLUGIN_ERROR_SIZE, "(the plugin gave no reason)")));
}

void PluginDrive::refresh_description() {
  char text[NETMC_DRIVE_PLUGIN_TEXT_SIZE] = {};
  ErrorBuffer error;
  description_ = table_->describe(drive_, text, sizeof text, error.text, sizeof error.text) == NETMC_DRIVE_OK
                     ? fmt::format("plugin:{} ({})", path_, plugin_text(text, sizeof text, "no description"))
                     : fmt::format("plugin:{} (describe failed: {})", path_, error.str());
}

void PluginDrive::open() {
  ErrorBuffer error;
  check(table_->open(drive_, error.text, sizeof error.text), "open", error.text);
  open_ = true;
  refresh_description();  // a driver may know its device only now
}

void PluginDrive::close() noexcept {
  if (!open_) return;
  open_ = false;
  ErrorBuffer error;
  if (table_->close(drive_, error.text, sizeof error.text) != NETMC_DRIVE_OK) {
    // close never throws: the node is leaving the drive either way, and says so.
    std::cerr << fmt::format("plugin {}: close: {}\n", path_, error.str());
  }
}

void PluginDrive::write_controlword(std::uint16_t word) {
  ErrorBuffer error;
  check(table_->write_controlword(drive_, word, error.text, sizeof error.text), "write_controlword", error.text);
}

void PluginDrive::write_mode(OperationMode mode) {
  require_mode(mode, "write_mode");
  ErrorBuffer error;
  check(table_->write_mode(drive_, static_cast<std::int8_t>(mode), error.text, sizeof error.text), "write_mode",
        error.text);
}

void PluginDrive::write_target(OperationMode mode, double value) {
  require_mode(mode, "write_target");
  if (!std::isfinite(value)) {
    throw DriveError(fmt::format("plugin {}: write_target in {}: {} is not finite", path_, operation_mode_name(mode), value));
  }
  ErrorBuffer error;
  check(table_->write_target(drive_, static_cast<std::int8_t>(mode), value, error.text, sizeof error.text),
        "write_target", error.text);
}

DriveFeedback PluginDrive::read() {
  netmc_drive_feedback raw{};
  ErrorBuffer error;
  check(table_->read(drive_, &raw, error.text, sizeof error.text), "read", error.text);
  DriveFeedback feedback;
  feedback.position_m = raw.position_m;
  feedback.velocity_m_s = raw.has_velocity ? raw.velocity_m_s : 0.0;
  feedback.has_velocity = raw.has_velocity != 0;
  feedback.statusword = raw.statusword;
  feedback.error_code = raw.error_code;
  return feedback;
}

void PluginDrive::cycle(double time_s) {
  ErrorBuffer error;
  check(table_->cycle(drive_, time_s, error.text, sizeof error.text), "cycle", error.text);
}

void PluginDrive::write_quick_stop_deceleration(double deceleration_m_s2) {
  if (!(deceleration_m_s2 > 0.0) || !std::isfinite(deceleration_m_s2)) {
    throw DriveError(fmt::format("plugin {}: write_quick_stop_deceleration: {} m/s^2 is not positive and finite", path_,
                                 deceleration_m_s2));
  }
  ErrorBuffer error;
  check(table_->write_quick_stop_deceleration(drive_, deceleration_m_s2, error.text, sizeof error.text),
        "write_quick_stop_deceleration", error.text);
}

}  // namespace netmc::drive
