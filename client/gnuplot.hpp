#pragma once
// Renders figures with gnuplot (Debian package gnuplot-nox): netmc writes the data files and
// a script, and runs `gnuplot SCRIPT` as a subprocess with a timeout. Each figure is written
// as PNG (pngcairo) and/or SVG, first under a temporary name and renamed when gnuplot has
// finished, so a failure leaves no half-drawn figure.

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace netmc::cli {

struct Figure {
  std::string name;        // file stem: <name>.png / <name>.svg
  int width_px = 1000;
  int height_px = 650;
  std::string body;        // gnuplot commands after `set terminal` / `set output`
};

struct FigureFormats {
  bool png = true;
  bool svg = true;
};

// The gnuplot executable: $NETMC_GNUPLOT if set, else `gnuplot` on PATH; nullopt if absent.
std::optional<std::string> find_gnuplot();

// Before a long run that ends in figures: throws std::runtime_error (as render_figures would)
// when gnuplot is missing.
void require_gnuplot();

// A path quoted for a gnuplot script ('...'). gnuplot runs backquoted text as a shell command
// except inside single quotes, a line break would end the command, and its escape of a quote
// ('') fails where two meet: throws std::invalid_argument for a path with a control character
// or a single quote.
std::string gnuplot_quote(const std::string& text);

// Text from outside (a run label, a file's content) as the inside of a single-quoted gnuplot
// string in enhanced-text mode, shown as it reads: quotes and backquotes become typographic
// apostrophes, enhanced-text markup is escaped and control characters become spaces, so it can
// neither leave the string nor reach a shell. Callers add the surrounding quotes.
std::string gnuplot_text(const std::string& text);

// Draws the figures into DIR (their data files in DIR/data, named relative to DIR) and keeps
// DIR/data/SET.gp, which redraws them in place (SET: "sim", "sweep"; one script per figure set,
// so one set does not overwrite another's). Returns the files written. Throws
// std::runtime_error when gnuplot is missing, fails (its message) or exceeds `timeout`.
std::vector<std::string> render_figures(const std::vector<Figure>& figures,
                                        const std::string& out_dir, FigureFormats formats,
                                        const std::string& set_name = "figures",
                                        std::chrono::milliseconds timeout = std::chrono::seconds(60));

}  // namespace netmc::cli
