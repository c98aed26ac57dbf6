#include "server/log/process_log.hpp"

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

namespace netmc::log {

void init(const std::string& program) {
  // Plain stderr (no colour codes in a file or journal), flushed every line: an operator tails it.
  auto logger = spdlog::stderr_logger_mt("process");
  logger->set_pattern("%Y-%m-%d %H:%M:%S.%e %-5l " + program + ": %v");
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

}  // namespace netmc::log
