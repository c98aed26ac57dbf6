#include "client/figures.hpp"

#include <fmt/format.h>
#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "client/study_report.hpp"
#include "control/controller_estimate.hpp"

namespace netmc::cli {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::invalid_argument(path.string() + ": cannot read the file");
  std::ostringstream content;
  content << file.rdbuf();
  return content.str();
}

std::string data_path(const std::string& data_dir, const std::string& name) {
  return (fs::absolute(data_dir) / name).string();
}

// How a script names a data file: relative to the figure directory (render_figures runs gnuplot
// there), so the kept script redraws in place wherever the directory is moved.
std::string in_script(const std::string& path) { return "data/" + fs::path(path).filename().string(); }

constexpr const char* kStyle =
    "set style line 1 lc rgb '#1f77b4' lw 2 pt 7 ps 0.8\n"
    "set style line 2 lc rgb '#d62728' lw 2 pt 5 ps 0.8\n"
    "set style line 3 lc rgb '#2ca02c' lw 2 pt 9 ps 0.9\n"
    "set style line 4 lc rgb '#9467bd' lw 2 pt 11 ps 0.9\n"
    "set style line 5 lc rgb '#ff7f0e' lw 2 pt 13 ps 0.9\n"
    "set style line 6 lc rgb '#8c564b' lw 2 pt 3 ps 0.9\n"
    "set style line 7 lc rgb '#e377c2' lw 2 pt 2 ps 0.9\n"
    "set style line 8 lc rgb '#17becf' lw 2 pt 4 ps 0.9\n"
    "set style increment user\n"
    "set grid lc rgb '#dddddd' lw 1\n"
    "set border lc rgb '#444444'\n";

int line_style(std::size_t index) { return static_cast<int>(index % 8) + 1; }
// The colours of line styles 1..8 above, for labels and markers.
constexpr std::array<const char*, 8> kColours{"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                              "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

// A single-axis run (thesis ch. 5) has x alone; its contour_error_m is the tracking error x - x_d.
bool single_axis(const CsvTable& table) { return !table.has_column("y_m"); }

// The columns the figures read; y_ref and y only where the run has a y axis (npos otherwise).
struct TraceColumns {
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t time, x_ref, y_ref, x, y, error, tau;
  explicit TraceColumns(const CsvTable& t)
      : time(t.column("time_s")), x_ref(t.column("x_ref_m")), y_ref(single_axis(t) ? kNone : t.column("y_ref_m")),
        x(t.column("x_m")), y(single_axis(t) ? kNone : t.column("y_m")), error(t.column("contour_error_m")),
        tau(t.column("tau_x_s")) {}
};

// First row of run `i`'s evaluation window (the steady metrics' window, e.g. after the thesis's
// start-up transient), or 0 when the run has none or the trace ends before it: the figures
// then show what the tables judge rather than a start-up peak hundreds of times larger.
std::size_t window_start_row(const SimOutputs& outputs, std::size_t i) {
  const double start_s = outputs.study.runs(static_cast<int>(i)).evaluation_start_s();
  const auto& table = outputs.traces[i].table;
  const std::size_t time = table.column("time_s");
  if (!(start_s > 0.0)) return 0;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    if (table.number(r, time) >= start_s) return r;
  }
  return 0;
}

std::string window_note(const SimOutputs& outputs) {
  if (window_start_row(outputs, 0) == 0) return "";
  return fmt::format(", t {} {:g} s", "\xE2\x89\xA5", outputs.study.runs(0).evaluation_start_s());
}

// "- 12.345" or "+ 12.345": the zoom axes count from the window centre.
std::string offset(double centre_mm) {
  return fmt::format("{} {:.3f}", centre_mm < 0.0 ? '+' : '-', std::abs(centre_mm));
}

Figure contour_figure(const SimOutputs& outputs, const std::string& data_dir) {
  // Zoom where the first run's contour error peaks in its evaluation window: the window shows
  // every run's deviation.
  const auto& first = outputs.traces.front().table;
  const TraceColumns c0(first);
  std::size_t peak = 0;
  double peak_error = -1.0;
  for (std::size_t r = window_start_row(outputs, 0); r < first.rows(); ++r) {
    if (std::abs(first.number(r, c0.error)) > peak_error) {
      peak_error = std::abs(first.number(r, c0.error));
      peak = r;
    }
  }
  // Centre the window between the actual point and the nearest desired sample, so both show.
  const double x_peak = first.number(peak, c0.x), y_peak = first.number(peak, c0.y);
  double nearest_distance = std::numeric_limits<double>::infinity();
  double x_near = x_peak, y_near = y_peak;
  for (std::size_t r = 0; r < first.rows(); ++r) {
    const double dx = first.number(r, c0.x_ref) - x_peak, dy = first.number(r, c0.y_ref) - y_peak;
    if (std::hypot(dx, dy) < nearest_distance) {
      nearest_distance = std::hypot(dx, dy);
      x_near = first.number(r, c0.x_ref);
      y_near = first.number(r, c0.y_ref);
    }
  }
  const double cx_mm = 0.5 * (x_peak + x_near) * 1e3;
  const double cy_mm = 0.5 * (y_peak + y_near) * 1e3;
  const double half_um = std::max(1.6 * peak_error * 1e6, 10.0);
  std::string plot_full = "plot ";
  std::string plot_zoom = "plot ";
  const auto run_title = [&](std::size_t i) {
    const auto& iterations = outputs.study.runs(static_cast<int>(i)).iterations();
    const bool unstable = !iterations.empty() && iterations[iterations.size() - 1].diverged();
    const bool not_following = !iterations.empty() && iterations[iterations.size() - 1].did_not_follow();
    return gnuplot_text(outputs.traces[i].label) +
           (unstable ? " (unstable)" : not_following ? " (did not follow the reference)" : "");
  };
  for (std::size_t i = 0; i < outputs.traces.size(); ++i) {
    const auto& table = outputs.traces[i].table;
    const TraceColumns c(table);
    std::string dat = "# x_ref_mm y_ref_mm x_mm y_mm dx_ref_um dy_ref_um dx_um dy_um (zoom: relative to the window centre)\n";
    for (std::size_t r = window_start_row(outputs, i); r < table.rows(); ++r) {
      const double xr = table.number(r, c.x_ref) * 1e3, yr = table.number(r, c.y_ref) * 1e3;
      const double x = table.number(r, c.x) * 1e3, y = table.number(r, c.y) * 1e3;
      dat += fmt::format("{:.6f} {:.6f} {:.6f} {:.6f} {:.4f} {:.4f} {:.4f} {:.4f}\n", xr, yr, x, y,
                         (xr - cx_mm) * 1e3, (yr - cy_mm) * 1e3, (x - cx_mm) * 1e3, (y - cy_mm) * 1e3);
    }
    const std::string path = data_path(data_dir, fmt::format("contour-{}.dat", i + 1));
    write_file_atomically(path, dat);
    plot_full += fmt::format("{} using 3:4 with lines ls {} title '{}', ", gnuplot_quote(in_script(path)),
                             line_style(i), run_title(i));
    plot_zoom += fmt::format("{} using 7:8 with lines ls {} title '{}', ", gnuplot_quote(in_script(path)),
                             line_style(i), run_title(i));
    if (i + 1 == outputs.traces.size()) {  // desired last, on top of the runs that hide it
      const std::string first_path = data_path(data_dir, "contour-1.dat");
      plot_full += gnuplot_quote(in_script(first_path)) + " using 1:2 with lines lc rgb 'black' dt 2 lw 1.5 title 'desired'";
      plot_zoom += gnuplot_quote(in_script(first_path)) + " using 5:6 with lines lc rgb 'black' dt 2 lw 1.5 title 'desired'";
    }
  }
  const double half_mm = half_um * 1e-3;
  // The full view frames the desired contour (a run that diverged leaves the frame).
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
  for (std::size_t r = 0; r < first.rows(); ++r) {
    x_lo = std::min(x_lo, first.number(r, c0.x_ref) * 1e3);
    x_hi = std::max(x_hi, first.number(r, c0.x_ref) * 1e3);
    y_lo = std::min(y_lo, first.number(r, c0.y_ref) * 1e3);
    y_hi = std::max(y_hi, first.number(r, c0.y_ref) * 1e3);
  }
  const double margin = std::max(0.15 * std::max(x_hi - x_lo, y_hi - y_lo), 0.5);
  Figure figure;
  figure.name = "contour";
  figure.width_px = 1300;
  figure.height_px = 620;
  figure.body = std::string(kStyle) + fmt::format(
      "set multiplot layout 1,2 title \"Desired vs actual contour (last iteration of each run; legend on the right)\" font ',13'\n"
      "set size ratio -1\n"
      "set xrange [{fx0:.6f}:{fx1:.6f}]\nset yrange [{fy0:.6f}:{fy1:.6f}]\n"
      "set xlabel 'x [mm]'\nset ylabel 'y [mm]'\n"
      "unset key\n"
      "set object 1 rect from {x0:.6f},{y0:.6f} to {x1:.6f},{y1:.6f} fs empty border lc rgb '#e6550d' lw 2 front\n"
      "set label 1 'zoom' at {x1:.6f},{y1:.6f} offset 0.5,0.5 tc rgb '#e6550d' front\n"
      "{full}\n"
      "unset object 1\nunset label 1\nset autoscale\n"
      "set title 'Zoom ({w:.0f} {mu}m square) where {first}\xE2\x80\x99s error peaks{window}' font ',12'\n"
      "set xrange [{mh:.4f}:{ph:.4f}]\nset yrange [{mh:.4f}:{ph:.4f}]\n"
      "set xlabel 'x {cx} mm [{mu}m]'\nset ylabel 'y {cy} mm [{mu}m]'\n"
      "set key bottom right box opaque samplen 3 font ',10'\n"
      "{zoom}\n",
      fmt::arg("fx0", x_lo - margin), fmt::arg("fx1", x_hi + margin),
      fmt::arg("fy0", y_lo - margin), fmt::arg("fy1", y_hi + margin),
      fmt::arg("x0", cx_mm - half_mm), fmt::arg("y0", cy_mm - half_mm), fmt::arg("x1", cx_mm + half_mm),
      fmt::arg("y1", cy_mm + half_mm), fmt::arg("full", plot_full), fmt::arg("zoom", plot_zoom),
      fmt::arg("w", 2 * half_um), fmt::arg("cx", offset(cx_mm)), fmt::arg("cy", offset(cy_mm)), fmt::arg("mh", -half_um),
      fmt::arg("ph", half_um), fmt::arg("mu", "\xC2\xB5"),
      fmt::arg("first", gnuplot_text(outputs.traces.front().label)), fmt::arg("window", window_note(outputs)));
  return figure;
}

Figure contour_error_figure(const SimOutputs& outputs, const std::string& data_dir) {
  const std::size_t n = outputs.traces.size();
  Figure figure;
  figure.name = "contour_error";
  figure.width_px = 1100;
  figure.height_px = static_cast<int>(std::max<std::size_t>(2, n)) * 190 + 110;
  // Fixed room in pixels at the top (title) and bottom (tick labels and the time label).
  const double bottom = 70.0 / figure.height_px, top = 1.0 - 45.0 / figure.height_px;
  // One axis: the error is the tracking error (thesis ch. 5's Figs. 5-5, 5-9).
  const bool tracking = single_axis(outputs.traces.front().table);
  std::string body = std::string(kStyle) + fmt::format(
      "set multiplot layout {},1 title \"{} vs time (last iteration of each run{})\" font ',13' "
      "margins 0.09,0.97,{:.4f},{:.4f} spacing 0,0.045\n"
      "set key top right box opaque samplen 1 font ',10'\nset ylabel '{} [{}m]'\nset format y '%g'\n"
      "set offsets 0, 0, graph 0.35, graph 0.05\n",
      n, tracking ? "Tracking error x - x_d" : "Contour error", window_note(outputs), bottom, top,
      tracking ? "x - x_d" : "e_c", "\xC2\xB5");
  for (std::size_t i = 0; i < n; ++i) {
    const auto& table = outputs.traces[i].table;
    const TraceColumns c(table);
    std::string dat = "# time_s contour_error_um\n";
    double max_um = 0.0;
    for (std::size_t r = window_start_row(outputs, i); r < table.rows(); ++r) {
      const double e_um = table.number(r, c.error) * 1e6;
      max_um = std::max(max_um, std::abs(e_um));
      dat += fmt::format("{:.6f} {:.5f}\n", table.number(r, c.time), e_um);
    }
    const std::string path = data_path(data_dir, fmt::format("contour_error-{}.dat", i + 1));
    write_file_atomically(path, dat);
    body += i + 1 == n ? "set xlabel 'time [s]'\nset format x '%g'\n" : "unset xlabel\nset format x ''\n";
    body += fmt::format("plot {} using 1:2 with lines ls {} title '{}  (max |{}| {:.2f} {}m)'\n",
                        gnuplot_quote(in_script(path)), line_style(i), gnuplot_text(outputs.traces[i].label),
                        tracking ? "x - x_d" : "e_c", max_um, "\xC2\xB5");
  }
  figure.body = body;
  return figure;
}

Figure e_sum_figure(const SimOutputs& outputs, const std::string& data_dir) {
  std::string plot = "plot ";
  for (int i = 0; i < outputs.study.runs_size(); ++i) {
    const auto& run = outputs.study.runs(i);
    std::string dat = "# iteration e_sum_mm e_max_mm\n";
    for (const auto& m : run.iterations()) {
      dat += fmt::format("{} {:.9g} {:.9g}\n", m.iteration(), m.e_sum_m() * 1e3, m.e_max_m() * 1e3);
    }
    const std::string path = data_path(data_dir, fmt::format("e_sum-{}.dat", i + 1));
    write_file_atomically(path, dat);
    plot += fmt::format("{} using 1:2 with linespoints ls {} title '{}'{}", gnuplot_quote(in_script(path)),
                        line_style(static_cast<std::size_t>(i)), gnuplot_text(run.label()),
                        i + 1 < outputs.study.runs_size() ? ", " : "");
  }
  Figure figure;
  figure.name = "e_sum";
  figure.body = std::string(kStyle) +
                "set title \"Learning: summed contour error per iteration\" font ',13'\n"
                "set logscale y\nset format y '10^{%L}'\n"
                "set xlabel 'iteration'\nset ylabel 'e_{sum} [mm]'\n"
                + std::string(outputs.study.runs(0).iterations_size() <= 25 ? "set xtics 1\n" : "") +
                "set key outside right top box samplen 2 font ',10'\n" + plot + "\n";
  return figure;
}

Figure tau_figure(const SimOutputs& outputs, const std::string& data_dir) {
  const auto& trace = outputs.traces.front();
  const TraceColumns c(trace.table);
  std::vector<double> taus_ms;
  for (std::size_t r = 0; r < trace.table.rows(); ++r) {
    const double tau = trace.table.number(r, c.tau);
    if (tau >= 0.0) taus_ms.push_back(tau * 1e3);
  }
  if (taus_ms.empty()) taus_ms.push_back(0.0);
  std::sort(taus_ms.begin(), taus_ms.end());
  const double lo = taus_ms.front(), hi = taus_ms.back();
  // One bin, centred on the value, when every setpoint saw the same delay.
  const int kBins = hi > lo ? 40 : 1;
  const double width = hi > lo ? (hi - lo) / kBins : std::max(0.02 * lo, 0.01);
  std::vector<int> counts(kBins, 0);
  for (const double tau : taus_ms) {  // the maximum belongs to the last bin
    counts[static_cast<std::size_t>(std::min<double>(kBins - 1, std::floor((tau - lo) / width)))]++;
  }
  std::string dat = "# tau_bin_centre_ms count\n";
  for (int b = 0; b < kBins; ++b) {
    dat += fmt::format("{:.6f} {}\n", hi > lo ? lo + (b + 0.5) * width : lo, counts[static_cast<std::size_t>(b)]);
  }
  const std::string path = data_path(data_dir, "tau_histogram.dat");
  write_file_atomically(path, dat);
  double mean = 0.0;
  for (const double tau : taus_ms) mean += tau;
  mean /= static_cast<double>(taus_ms.size());
  const double p99 = taus_ms[static_cast<std::size_t>(0.99 * static_cast<double>(taus_ms.size() - 1))];
  Figure figure;
  figure.name = "tau_histogram";
  figure.body = std::string(kStyle) + fmt::format(
      "set title 'Loop delay {tau} of the x axis: {run}, last iteration ({n} setpoints)' font ',13'\n"
      "set xlabel '{tau} = setpoint arrival - sample time [ms]'\nset ylabel 'setpoints per bin'\n"
      "set style fill solid 0.55 border lc rgb '#1f4e79'\nset boxwidth {w:.6f} absolute\n"
      "set yrange [0:*]\nset offsets graph 0.1, graph 0.1, graph 0.15, 0\n{xrange}"
      "set key top left box opaque samplen 2 font ',10'\n"
      "set arrow 1 from {mean:.6f}, graph 0 to {mean:.6f}, graph 1 nohead lc rgb '#d62728' lw 2 dt 2\n"
      "set arrow 2 from {p99:.6f}, graph 0 to {p99:.6f}, graph 1 nohead lc rgb '#ff7f0e' lw 2 dt 3\n"
      "plot {path} using 1:2 with boxes lc rgb '#4a90d9' title 'bin width {w:.3f} ms', "
      "NaN with lines lc rgb '#d62728' lw 2 dt 2 title 'mean {mean:.3f} ms', "
      "NaN with lines lc rgb '#ff7f0e' lw 2 dt 3 title 'p99 {p99:.3f} ms'\n",
      fmt::arg("tau", "\xCF\x84"), fmt::arg("run", gnuplot_text(trace.label)), fmt::arg("n", taus_ms.size()),
      fmt::arg("w", width), fmt::arg("mean", mean),
      fmt::arg("xrange", hi > lo ? std::string() : fmt::format("set xrange [{:.6f}:{:.6f}]\n", lo - 10 * width, lo + 10 * width)), fmt::arg("p99", p99), fmt::arg("path", gnuplot_quote(in_script(path))));
  return figure;
}

// Unit and scale of a metric column for the axis label.
std::pair<std::string, double> display_unit(const std::string& metric) {
  const auto ends_with = [&](const std::string& suffix) {
    return metric.size() > suffix.size() &&
           metric.compare(metric.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends_with("_m")) return {"mm", 1e3};
  if (ends_with("_s")) return {"ms", 1e3};
  return {"", 1.0};
}

// e_max_m -> "e_{max}" (gnuplot enhanced text), tau_p99_s -> "τ_{p99}".
std::string metric_label(const std::string& metric) {
  std::string name = metric;
  for (const std::string suffix : {"_m", "_s"}) {
    if (name.size() > suffix.size() && name.ends_with(suffix)) {
      name = name.substr(0, name.size() - suffix.size());
      break;
    }
  }
  const std::size_t underscore = name.find('_');
  std::string head = gnuplot_text(name.substr(0, underscore));
  if (head == "tau") head = "\xCF\x84";
  if (underscore == std::string::npos) return head;
  std::string rest = name.substr(underscore + 1);
  std::replace(rest.begin(), rest.end(), '_', ' ');
  return head + "_{" + gnuplot_text(rest) + "}";
}

}  // namespace

SimOutputs load_sim_outputs(const std::string& dir) {
  const fs::path root(dir);
  const fs::path results = root / kSimResultsFile;
  SimOutputs outputs;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = true;
  const auto status = google::protobuf::util::JsonStringToMessage(read_text(results), &outputs.study, options);
  if (!status.ok()) {
    throw std::invalid_argument(results.string() + ": not a netmc results file: " + std::string(status.message()));
  }
  if (outputs.study.runs_size() == 0) throw std::invalid_argument(results.string() + ": no runs");
  for (int i = 0; i < outputs.study.runs_size(); ++i) {
    const fs::path trace = root / kSimTracesDir / trace_file_name(static_cast<std::size_t>(i), outputs.study.runs(i).label());
    outputs.traces.push_back({outputs.study.runs(i).label(), CsvTable::read(trace.string())});
    if (outputs.traces.back().table.rows() == 0) throw std::invalid_argument(trace.string() + ": no rows");
    TraceColumns check(outputs.traces.back().table);  // throws naming a missing column
  }
  return outputs;
}

namespace {

// The controller-estimate columns of a trace: those after tau_x_s, named NAME[UNIT].
struct EstimateColumn {
  std::size_t column;
  std::string name, unit;
};
std::vector<EstimateColumn> estimate_columns(const CsvTable& table) {
  std::vector<EstimateColumn> out;
  if (!table.has_column("tau_x_s")) return out;
  const auto& header = table.header();
  for (std::size_t c = table.column("tau_x_s") + 1; c < header.size(); ++c) {
    const std::string& h = header[c];
    const std::size_t open = h.find('[');
    if (open == std::string::npos || h.back() != ']') continue;
    out.push_back({c, h.substr(0, open), h.substr(open + 1, h.size() - open - 2)});
    // A trace file is input like any other: no more panels than a controller can write.
    if (out.size() == control::kMaxControllerEstimates) break;
  }
  return out;
}

// Each adaptive controller's estimates over time, one panel per estimate (the thesis's
// Figs. 3-10 to 3-13): one figure per run that has any.
std::vector<Figure> estimate_figures(const SimOutputs& outputs, const std::string& data_dir) {
  constexpr std::size_t kMaxPoints = 4000;  // per series: enough for the eye, small files
  std::vector<Figure> figures;
  for (std::size_t i = 0; i < outputs.traces.size(); ++i) {
    const auto& table = outputs.traces[i].table;
    const auto columns = estimate_columns(table);
    if (columns.empty() || table.rows() == 0) continue;
    const std::size_t time = table.column("time_s");
    const std::size_t stride = std::max<std::size_t>(1, table.rows() / kMaxPoints);
    Figure figure;
    figure.name = fmt::format("estimates-{}", i + 1);
    const std::size_t n = columns.size();
    const std::size_t layout_columns = n > 4 ? 2 : 1;
    const std::size_t layout_rows = (n + layout_columns - 1) / layout_columns;
    figure.width_px = layout_columns == 2 ? 1300 : 1000;
    figure.height_px = static_cast<int>(layout_rows) * 170 + 110;
    std::string body = std::string(kStyle) + fmt::format(
        "set multiplot layout {},{} title '{}: controller estimates (last iteration)' font ',13'\n"
        "set key off\nset format y '%g'\nset xlabel 'time [s]'\n",
        layout_rows, layout_columns, gnuplot_text(outputs.traces[i].label));
    for (std::size_t e = 0; e < n; ++e) {
      std::string dat = "# time_s value\n";
      for (std::size_t r = 0; r < table.rows(); r += stride) {
        dat += fmt::format("{:.6f} {:.9g}\n", table.number(r, time), table.number(r, columns[e].column));
      }
      const std::string path = data_path(data_dir, fmt::format("estimates-{}-{}.dat", i + 1, e + 1));
      write_file_atomically(path, dat);
      body += fmt::format("set ylabel '{} [{}]'\nplot {} using 1:2 with lines ls {}\n", gnuplot_text(columns[e].name),
                          gnuplot_text(columns[e].unit), gnuplot_quote(in_script(path)), line_style(e));
    }
    body += "unset multiplot\n";
    figure.body = body;
    figures.push_back(figure);
  }
  return figures;
}

}  // namespace

std::vector<Figure> sim_figures(const SimOutputs& outputs, const std::string& data_dir) {
  // The contour figure needs a plane; a study of single-axis runs has none.
  const bool planar = std::none_of(outputs.traces.begin(), outputs.traces.end(),
                                   [](const auto& trace) { return single_axis(trace.table); });
  std::vector<Figure> figures;
  if (planar) figures.push_back(contour_figure(outputs, data_dir));
  for (auto figure : {contour_error_figure(outputs, data_dir), e_sum_figure(outputs, data_dir),
                      tau_figure(outputs, data_dir)}) {
    figures.push_back(std::move(figure));
  }
  for (auto& figure : estimate_figures(outputs, data_dir)) figures.push_back(std::move(figure));
  return figures;
}

std::vector<Figure> sweep_figures(const CsvTable& sweep, const std::vector<std::string>& metrics,
                                  const std::string& data_dir) {
  const std::size_t config = sweep.column("config"), base = sweep.column("base"),
                    run = sweep.column("run"), delay = sweep.column("delay_max_s"),
                    iteration = sweep.column("iteration"), diverged = sweep.column("diverged"),
                    not_following = sweep.column("did_not_follow");
  // The last row of each configuration is its last iteration.
  std::map<long long, std::size_t> last_row;
  for (std::size_t r = 0; r < sweep.rows(); ++r) {
    const auto key = static_cast<long long>(sweep.number(r, config));
    const auto found = last_row.find(key);
    if (found == last_row.end() || sweep.number(r, iteration) >= sweep.number(found->second, iteration)) {
      last_row[key] = r;
    }
  }
  std::set<std::string> bases;
  for (const auto& [key, r] : last_row) bases.insert(sweep.text(r, base));
  // The delays' lower bound, stated on the axis: the same for every configuration of a delay
  // sweep ("uniform 300 us..800 us" -> "300 us"), else left out.
  std::set<std::string> lower_bounds;
  const std::size_t delay_text = sweep.column("delay");
  for (const auto& [key, r] : last_row) {
    const std::string text = sweep.text(r, delay_text);
    const auto from = text.rfind("uniform "), to = text.rfind("..");
    lower_bounds.insert(from != std::string::npos && to != std::string::npos && to > from + 8
                            ? text.substr(from + 8, to - from - 8)
                            : std::string());
  }
  const std::string lower_bound =
      lower_bounds.size() == 1 && !lower_bounds.begin()->empty()
          ? " (each delay uniform from " + gnuplot_text(*lower_bounds.begin()) + " up to it)"
          : std::string();

  std::vector<Figure> figures;
  for (const auto& metric : metrics) {
    const std::size_t column = sweep.column(metric);
    const auto [unit, scale] = display_unit(metric);
    // series (base, run) in order of appearance -> delay -> values of the stable seeds
    std::vector<std::string> series_order;
    std::map<std::string, std::map<double, std::vector<double>>> values;
    std::map<std::string, int> unstable;
    for (const auto& [key, r] : last_row) {
      const std::string series = bases.size() > 1 ? sweep.text(r, base) + ": " + sweep.text(r, run) : sweep.text(r, run);
      if (!values.contains(series)) series_order.push_back(series);
      auto& by_delay = values[series];
      const double delay_ms = sweep.number(r, delay) * 1e3;
      if (std::isnan(delay_ms)) continue;
      auto& cell = by_delay[delay_ms];
      if (sweep.number(r, diverged) != 0.0) {
        ++unstable[series];
        continue;
      }
      if (sweep.text(r, not_following) == "1") continue;  // no result to plot (study_report.cpp)
      cell.push_back(sweep.number(r, column) * scale);
    }
    std::vector<std::string> elements;
    std::string markers;  // a cross at the top for each delay where every seed was unstable
    bool positive = true;
    bool any_point = false;
    double lowest = std::numeric_limits<double>::infinity(), highest = 0.0;
    for (std::size_t s = 0; s < series_order.size(); ++s) {
      const auto& series = series_order[s];
      std::string dat = "# delay_max_ms mean min max stable_seeds\n";
      bool has_point = false;
      for (const auto& [delay_ms, cell] : values[series]) {
        if (cell.empty()) {
          dat += fmt::format("{:.6f} NaN NaN NaN 0\n", delay_ms);
          markers += fmt::format("set label at first {:.6f}, graph {:.3f} point pt 2 ps 1.6 lw 2 lc rgb '{}' front\n",
                                 delay_ms, 0.965 - 0.025 * static_cast<double>(s % 4), kColours[s % 8]);
          continue;
        }
        has_point = true;
        double sum = 0.0;
        for (const double v : cell) sum += v;
        const auto [lo, hi] = std::minmax_element(cell.begin(), cell.end());
        positive = positive && *lo > 0.0;
        lowest = std::min(lowest, *lo);
        highest = std::max(highest, *hi);
        dat += fmt::format("{:.6f} {:.9g} {:.9g} {:.9g} {}\n", delay_ms, sum / static_cast<double>(cell.size()),
                           *lo, *hi, cell.size());
      }
      any_point = any_point || has_point;
      const std::string path = data_path(data_dir, fmt::format("sweep-{}-{}.dat", metric, s + 1));
      write_file_atomically(path, dat);
      if (!has_point) {  // keep it in the legend, without a line
        elements.push_back(fmt::format("NaN with linespoints ls {} title '{} (unstable everywhere)'",
                                       line_style(s), gnuplot_text(series)));
        continue;
      }
      const std::string title = gnuplot_text(series) + (unstable[series] > 0
                                                     ? fmt::format(" ({} unstable)", unstable[series])
                                                     : std::string());
      elements.push_back(fmt::format(
          "{p} using 1:3:4 with filledcurves ls {ls} fs transparent solid 0.18 noborder notitle, "
          "{p} using 1:2 with linespoints ls {ls} title '{t}'",
          fmt::arg("p", gnuplot_quote(in_script(path))), fmt::arg("ls", line_style(s)), fmt::arg("t", title)));
    }
    if (!any_point) {
      throw std::invalid_argument("sweep CSV: no configuration has both a delay upper bound (delay_max_s) and a stable last iteration "
                                  "to plot " + metric + " against (pareto without max and trace delays have no bound)");
    }
    if (!markers.empty()) {
      elements.push_back("NaN with points pt 2 ps 1.6 lw 2 lc rgb '#444444' title 'x at the top: unstable in every seed'");
    }
    std::string plot = markers + "plot ";
    for (std::size_t e = 0; e < elements.size(); ++e) plot += (e == 0 ? std::string() : std::string(", ")) + elements[e];
    Figure figure;
    figure.name = "sweep-" + metric;
    figure.width_px = 1150;
    figure.height_px = 650;
    const std::string label = metric_label(metric) + (unit.empty() ? "" : " [" + unit + "]");
    figure.body = std::string(kStyle) + fmt::format(
        "set title '{label} of the last iteration vs loop-delay upper bound (mean over seeds, band: min-max)' font ',12'\n"
        "set xlabel 'loop delay upper bound [ms]{lower}'\nset ylabel '{label}'\n"
        "{log}set key outside right top vertical box samplen 2 font ',10'\n"
        "set datafile missing 'NaN'\n{room}{plot}\n",
        fmt::arg("label", label), // Log scale only when the values span more than about a decade and a half: fewer decades
        // would leave one or two labelled ticks.
        fmt::arg("log", positive && metric.starts_with("e_") && highest > 30.0 * lowest ? "set logscale y\nset format y '%g'\n" : ""),
        fmt::arg("room", markers.empty() ? "" : "set offsets 0, 0, graph 0.15, 0\n"), fmt::arg("plot", plot),
        fmt::arg("lower", lower_bound));
    figures.push_back(std::move(figure));
  }
  return figures;
}

}  // namespace netmc::cli
