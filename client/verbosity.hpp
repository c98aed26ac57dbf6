#pragma once
// --quiet / --verbose on every subcommand, and the process logger they set: spdlog to stderr,
// warnings by default, info with --verbose, off with --quiet. Error messages that end a
// command are not log lines: they are printed even with --quiet.

#include <CLI/CLI.hpp>

namespace netmc::cli {

struct Verbosity {
  bool quiet = false;
  bool verbose = false;
};

// The one instance of the process (set by the flags while parsing).
Verbosity& verbosity();
void add_verbosity_flags(CLI::App* app);
// Installs the stderr logger at the level the flags ask for.
void configure_logging();

}  // namespace netmc::cli
