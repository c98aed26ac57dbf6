#pragma once
// `netmc qft`: paper 004's QFT check of a cross-coupled contour controller C(s) (section 3.2):
// per design frequency, the worst of the 21 template points of |S| (eq. 16) and of |T|/|T_u|
// (eqs. 17, 18), beside an independent check's numbers; optionally Bode and Nichols figures.

#include <CLI/CLI.hpp>

#include <functional>

namespace netmc::cli {

std::function<int()> add_qft_command(CLI::App& app);

}  // namespace netmc::cli
