#include "client/plot_command.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "client/figures.hpp"
#include "client/spec_syntax.hpp"

namespace netmc::cli {

FigureFormats parse_figure_formats(const std::string& text, const std::string& flag) {
  FigureFormats formats{false, false};
  const auto items = split_list(text);
  for (const auto& item : items) {
    if (item == "png") {
      formats.png = true;
    } else if (item == "svg") {
      formats.svg = true;
    } else {
      throw std::invalid_argument(flag + ": expected png, svg or png,svg, got '" + text + "'");
    }
  }
  if (items.empty()) throw std::invalid_argument(flag + ": expected png, svg or png,svg, got '" + text + "'");
  return formats;
}

std::vector<std::string> plot_sim_outputs(const std::string& dir, const std::string& out_dir,
                                          FigureFormats formats) {
  const SimOutputs outputs = load_sim_outputs(dir);
  const std::string data_dir = (std::filesystem::path(out_dir) / "data").string();
  std::filesystem::create_directories(data_dir);
  return render_figures(sim_figures(outputs, data_dir), out_dir, formats, "sim");
}

std::function<int()> add_plot_command(CLI::App& app) {
  struct Flags {
    std::string sim_dir, sweep_csv, out_dir, format = "png,svg", metrics = "e_max_m,e_sum_m";
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* plot = app.add_subcommand(
      "plot", "Draw figures (PNG, SVG; with gnuplot) from a sim run's outputs or a sweep's CSV");
  auto* sim = plot->add_option("--sim", flags->sim_dir,
                               "A directory written by `netmc sim --plot DIR` (results.json, traces/)")
                   ->type_name("DIR");
  auto* sweep = plot->add_option("--sweep", flags->sweep_csv, "A CSV written by `netmc sweep --csv`")
                     ->type_name("FILE.csv");
  sim->excludes(sweep);
  plot->add_option("--out", flags->out_dir, "Directory for the figures (default: the --sim directory, "
                                            "or the sweep CSV's directory)")
      ->type_name("DIR");
  plot->add_option("--metric", flags->metrics,
                   "Sweep metrics to plot against the delay, comma-separated CSV columns "
                   "(default e_max_m,e_sum_m)")
      ->type_name("COLUMN[,...]");
  plot->add_option("--format", flags->format, "png, svg or png,svg (default)")->type_name("FORMATS");
  plot->footer(R"(Examples:
  netmc sim --plot figures                 # runs the study and draws its figures in one go
  netmc plot --sim figures --format svg    # redraws them from figures/results.json, figures/traces/
  netmc sweep --delay-max 0.5ms:10ms:20 --seeds 1..5 --iterations 10 --csv sweep.csv
  netmc plot --sweep sweep.csv --out figures --metric e_max_m,e_rms_m,tau_p99_s

Figures from --sim: contour (desired vs actual, with a zoom panel where the first run's error
peaks), contour_error (vs time, one panel per run), e_sum (vs iteration, log scale),
tau_histogram (loop delay of the first run). From --sweep: sweep-METRIC (mean over seeds with
the min-max band, one line per run; unstable configurations left out and counted).
gnuplot (Debian package gnuplot-nox) draws them; data files and the script are kept in
OUT/data/ (sim.gp or sweep.gp: cd OUT && gnuplot data/sim.gp redraws in place) for editing.)");

  return [flags]() -> int {
    if (flags->sim_dir.empty() && flags->sweep_csv.empty()) {
      throw std::invalid_argument("plot: expected --sim DIR or --sweep FILE.csv");
    }
    const FigureFormats formats = parse_figure_formats(flags->format, "--format");
    std::vector<std::string> written;
    if (!flags->sim_dir.empty()) {
      const std::string out = flags->out_dir.empty() ? flags->sim_dir : flags->out_dir;
      written = plot_sim_outputs(flags->sim_dir, out, formats);
    } else {
      const auto metrics = split_list(flags->metrics);
      if (metrics.empty()) throw std::invalid_argument("--metric: expected COLUMN[,COLUMN...] such as e_max_m");
      const CsvTable table = CsvTable::read(flags->sweep_csv);
      for (const auto& metric : metrics) {
        // The name becomes part of a file name and a figure label: letters, digits, _ only.
        const bool plain_name = !metric.empty() && metric.size() <= 64 &&
                                std::all_of(metric.begin(), metric.end(), [](char c) {
                                  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
                                });
        if (!plain_name) {
          throw std::invalid_argument("--metric: expected column names of letters, digits and _ (such as e_max_m)");
        }
        if (!table.has_column(metric)) {
          throw std::invalid_argument(fmt::format("--metric: '{}' is not a column of {} (e.g. e_max_m, "
                                                  "e_sum_m, e_rms_m, tau_p99_s)", metric, flags->sweep_csv));
        }
      }
      std::string out = flags->out_dir;
      if (out.empty()) {
        out = std::filesystem::path(flags->sweep_csv).parent_path().string();
        if (out.empty()) out = ".";
      }
      const std::string data_dir = (std::filesystem::path(out) / "data").string();
      std::filesystem::create_directories(data_dir);
      written = render_figures(sweep_figures(table, metrics, data_dir), out, formats, "sweep");
    }
    for (const auto& file : written) fmt::print("wrote {}\n", file);
    return 0;
  };
}

}  // namespace netmc::cli
