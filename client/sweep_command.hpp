#pragma once
// `netmc sweep`: a grid of studies (base x controller x delay x seed) run in-process on all
// cores (or on a netmc-server), written as a tidy CSV and JSON once everything has run.

#include <CLI/CLI.hpp>

#include <functional>

namespace netmc::cli {

std::function<int()> add_sweep_command(CLI::App& app);

}  // namespace netmc::cli
