#pragma once
// The commissioning commands: netmc enable, disable, quick-stop, move and jog move one axis that
// no job holds, through the server and the axis's node, which checks each against the axis's
// limits and supervises the motion (server/axis/commissioning_axis.hpp).

#include <CLI/CLI.hpp>

#include <functional>

namespace netmc::cli {

// Registers the five subcommands; the returned function runs whichever was given (0 when none
// of them was).
std::function<int()> add_commissioning_commands(CLI::App& app);

}  // namespace netmc::cli
