#pragma once
// `netmc plot`: figures (PNG and SVG, drawn by gnuplot) from a sim run's saved outputs or from
// a sweep's CSV.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "client/gnuplot.hpp"

namespace netmc::cli {

std::function<int()> add_plot_command(CLI::App& app);

// "png,svg" | "png" | "svg"; throws std::invalid_argument naming `flag`.
FigureFormats parse_figure_formats(const std::string& text, const std::string& flag);
// Renders the standard sim figures of DIR (results.json + traces/) into `out_dir`.
std::vector<std::string> plot_sim_outputs(const std::string& dir, const std::string& out_dir,
                                          FigureFormats formats);

}  // namespace netmc::cli
