#include "client/verbosity.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <stdexcept>

namespace netmc::cli {

Verbosity& verbosity() {
  static Verbosity instance;
  return instance;
}

void add_verbosity_flags(CLI::App* app) {
  auto* quiet = app->add_flag("-q,--quiet", verbosity().quiet,
                              "Print only results and errors (no progress, no log)");
  auto* verbose = app->add_flag("-v,--verbose", verbosity().verbose,
                                "Log what is being done (info level) on stderr");
  quiet->excludes(verbose);
}

void configure_logging() {
  auto logger = spdlog::get("netmc");
  if (!logger) logger = spdlog::stderr_color_mt("netmc");
  logger->set_pattern("netmc: %^%l%$: %v");
  spdlog::set_default_logger(logger);
  const Verbosity& v = verbosity();
  // The flags may sit on netmc and on the subcommand, where CLI11 cannot see both at once.
  if (v.quiet && v.verbose) throw std::invalid_argument("--quiet: cannot be combined with --verbose");
  spdlog::set_level(v.quiet ? spdlog::level::off
                            : v.verbose ? spdlog::level::info : spdlog::level::warn);
}

}  // namespace netmc::cli
