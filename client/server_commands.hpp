#pragma once
// `netmc run` (a study on a running netmc-server) and `netmc nodes` (its discovered axis nodes).

#include <CLI/CLI.hpp>

#include <functional>

namespace netmc::cli {

std::function<int()> add_run_command(CLI::App& app);
std::function<int()> add_nodes_command(CLI::App& app);

}  // namespace netmc::cli
