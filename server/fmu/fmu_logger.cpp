#include "server/fmu/fmu_logger.hpp"

#include <cstdarg>
#include <cstdio>

#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {
namespace {

constexpr std::size_t kMaxInstancesRemembered = 64;

}  // namespace

std::string_view fmi2_status_name(fmi2Status status) {
  switch (status) {
    case fmi2OK: return "fmi2OK";
    case fmi2Warning: return "fmi2Warning";
    case fmi2Discard: return "fmi2Discard";
    case fmi2Error: return "fmi2Error";
    case fmi2Fatal: return "fmi2Fatal";
    case fmi2Pending: return "fmi2Pending";
  }
  return "an unknown fmi2Status";
}

FmuLogger::FmuLogger(std::string fmu_name, std::size_t max_lines)
    : fmu_name_(printable_text(fmu_name)), max_lines_(max_lines) {}

void FmuLogger::log(fmi2ComponentEnvironment environment, fmi2String instance_name, fmi2Status status,
                    fmi2String category, fmi2String message, ...) {
  if (environment == nullptr || status == fmi2OK || message == nullptr) return;
  // The message is a printf format for the trailing arguments (FMI 2.0, 2.1.5).
  char text[kMaxLogMessageLength + 1];
  va_list arguments;
  va_start(arguments, message);
  const int length = std::vsnprintf(text, sizeof text, message, arguments);
  va_end(arguments);
  if (length < 0) return;
  try {
    static_cast<FmuLogger*>(environment)
        ->record(instance_name ? instance_name : "", status, category ? category : "", text);
  } catch (...) {
    // Out of memory while logging: the message is lost, the FMU's call goes on.
  }
}

void FmuLogger::record(std::string_view instance_name, fmi2Status status, std::string_view category,
                       std::string_view text) {
  const std::string message = printable_text(text, kMaxLogMessageLength);
  {
    std::lock_guard lock(mutex_);
    const std::string instance(printable_text(instance_name, 64));
    if (last_.size() < kMaxInstancesRemembered || last_.count(instance) != 0) last_[instance] = message;
  }
  const std::size_t line = lines_.fetch_add(1);
  // Appended piece by piece (one line, written at once): GCC 12 misreads long operator+ chains.
  std::string out = "fmu ";
  out += fmu_name_;
  if (line < max_lines_) {
    out += " [";
    out += printable_text(instance_name, 64);
    out += "] ";
    out += fmi2_status_name(status);
    if (!category.empty()) {
      out += ' ';
      out += printable_text(category, 64);
    }
    out += ": ";
    out += message;
  } else if (line == max_lines_) {
    out += ": further messages of this FMU suppressed (";
    out += std::to_string(max_lines_);
    out += " lines shown)";
  } else {
    lines_.store(max_lines_ + 1);  // keep the counter from wrapping in a long run
    return;
  }
  out += '\n';
  std::fwrite(out.data(), 1, out.size(), stderr);
}

std::string FmuLogger::last_message(std::string_view instance_name) const {
  std::lock_guard lock(mutex_);
  const auto found = last_.find(printable_text(instance_name, 64));
  return found == last_.end() ? std::string() : found->second;
}

}  // namespace netmc::plant::fmu
