#pragma once
// The whole `netmc` command line as a function, so tests can run it in-process: parses,
// runs the subcommand and maps errors to exit codes (2: usage or bad input, 1: failure).

namespace netmc::cli {

int run_netmc(int argc, const char* const* argv);

}  // namespace netmc::cli
