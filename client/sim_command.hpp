#pragma once
// `netmc sim`: the in-process study in virtual time.

#include <CLI/CLI.hpp>

namespace netmc::cli {

// Registers the subcommand and its flags; the returned callback runs it (exit code).
std::function<int()> add_sim_command(CLI::App& app);

}  // namespace netmc::cli
