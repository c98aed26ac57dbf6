#pragma once
// The logger callback netmc hands an FMU (FMI 2.0, 2.1.5: fmi2CallbackLogger, with the FmuLogger
// as the componentEnvironment). Messages of status fmi2OK are informational and dropped; warnings
// and worse go to stderr as one line each, "fmu PATH [instance] status category: message" (made
// printable, cut at kMaxLogMessageLength), at most kMaxLogLines lines per loaded model, then one
// line saying the rest is suppressed: a chatty model cannot flood a node's log. The last warning
// or error of each instance is kept for the exception of a failed call. Callable from any thread;
// never throws (it runs inside the FMU's code).

#include <atomic>
#include <cstddef>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>

#include "server/fmu/fmi2_api.h"

namespace netmc::plant::fmu {

inline constexpr std::size_t kMaxLogLines = 100;
inline constexpr std::size_t kMaxLogMessageLength = 500;

class FmuLogger {
 public:
  explicit FmuLogger(std::string fmu_name, std::size_t max_lines = kMaxLogLines);
  FmuLogger(const FmuLogger&) = delete;
  FmuLogger& operator=(const FmuLogger&) = delete;

  // The fmi2CallbackLogger; componentEnvironment must be an FmuLogger.
  static void log(fmi2ComponentEnvironment environment, fmi2String instance_name, fmi2Status status,
                  fmi2String category, fmi2String message, ...);

  // The last warning or error `instance_name` reported, "" when none.
  std::string last_message(std::string_view instance_name) const;
  // Lines written to stderr so far (the suppression notice included).
  std::size_t lines_written() const { return lines_.load(); }

 private:
  void record(std::string_view instance_name, fmi2Status status, std::string_view category, std::string_view text);

  std::string fmu_name_;
  std::size_t max_lines_;
  std::atomic<std::size_t> lines_{0};
  mutable std::mutex mutex_;
  std::unordered_map<std::string, std::string> last_;  // by instance name; netmc names a few instances
};

// "fmi2OK", "fmi2Error", ...
std::string_view fmi2_status_name(fmi2Status status);

}  // namespace netmc::plant::fmu
