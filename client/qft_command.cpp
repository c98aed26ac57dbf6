#include "client/qft_command.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "client/exclusive_file.hpp"
#include "client/gnuplot.hpp"
#include "client/plot_command.hpp"
#include "client/spec_syntax.hpp"
#include "client/study_report.hpp"
#include "control/frequency/qft_bounds.hpp"

namespace netmc::cli {
namespace {

namespace fs = std::filesystem;

// An independent check's values for one design frequency, printed as text beside the measured ones:
// paper 004's bounds evaluated on its plants (Tables 1/2) with z_lp = 0.7, independently of netmc. The paper
// prints only the verdicts (eq. 19 fails the stability bound at 35 Hz, eq. 20 meets both: section 3.2.3).
struct ReferenceValue {
  double frequency_hz;
  std::string max_sensitivity;     // "" where it states none
  std::string max_tracking_ratio;
};

struct CrossCouplingDesign {
  const char* flag_value;  // --ccc
  const char* title;
  control::TransferFunction (*make)();
  std::vector<ReferenceValue> reference;
};

control::TransferFunction table3_pid() { return control::paper004_pid_cross_coupling(); }

std::vector<CrossCouplingDesign> designs() {
  // The independent check: max|S| = 0.10 (0.1-1 Hz), 0.215 (10 Hz), 0.71 (35 Hz) and max |T|/|T_u|
  // <= 0.917 at every design frequency.
  std::vector<ReferenceValue> eq20;
  for (const double f : control::qft_design_frequencies_hz()) {
    const std::string sensitivity = f <= 1.0 ? "0.10" : (f == 10.0 ? "0.215" : (f == 35.0 ? "0.71" : ""));
    eq20.push_back({f, sensitivity, "<=0.917"});
  }
  return {
      {"eq20", "paper 004, eq. 20: the QFT design", &control::paper004_eq20_cross_coupling, eq20},
      {"eq19", "paper 004, eq. 19: the first try", &control::paper004_eq19_cross_coupling, {{35.0, "", "1.056"}}},
      {"lpccc", "paper 004, eq. 13 with Table 3: PID-type cross-coupling", &table3_pid, {{10.0, "0.53", ""}}},
  };
}

std::vector<CrossCouplingDesign> selected_designs(const std::string& text) {
  const auto all = designs();
  const std::string choices = "eq20, eq19 or lpccc";
  std::vector<CrossCouplingDesign> chosen;
  const auto items = split_list(text);
  if (items.empty()) throw std::invalid_argument("--ccc: expected " + choices + " (comma separated)");
  for (const auto& item : items) {
    const auto found = std::find_if(all.begin(), all.end(), [&](const auto& d) { return item == d.flag_value; });
    if (found == all.end()) {
      throw std::invalid_argument("--ccc: unknown controller '" + item + "', expected " + choices);
    }
    const bool repeated = std::any_of(chosen.begin(), chosen.end(), [&](const auto& d) { return item == d.flag_value; });
    if (!repeated) chosen.push_back(*found);
  }
  return chosen;
}

const ReferenceValue* reference_at(const CrossCouplingDesign& design, double f) {
  for (const auto& value : design.reference) {
    if (value.frequency_hz == f) return &value;
  }
  return nullptr;
}

std::string or_dash(const std::string& text) { return text.empty() ? "-" : text; }

void print_table(const CrossCouplingDesign& design, const control::TransferFunction& cross_coupling,
                 const std::vector<control::QftBoundCheck>& checks) {
  fmt::print("{}\n  C(s) = {}\n", design.title, cross_coupling.describe());
  fmt::print("  {:>7}  {:>7}  {:>5}  {:>7}  {:>12}  {:>7}  {}\n", "f [Hz]", "max|S|", "bound", "ref",
             "max|T|/|T_u|", "ref", "verdict");
  std::vector<std::string> violations;
  for (const auto& check : checks) {
    const bool sensitivity_checked = check.frequency_hz <= control::kQftSensitivityBoundMaxFrequencyHz;
    const bool sensitivity_ok = !sensitivity_checked || check.max_sensitivity <= control::kQftSensitivityBound;
    const bool tracking_ok = check.max_tracking_ratio <= 1.0;
    std::vector<std::string> failed;
    if (!sensitivity_ok) failed.push_back("eq. 16");
    if (!tracking_ok) failed.push_back("eq. 17");
    if (!failed.empty()) violations.push_back(fmt::format("{:g} Hz", check.frequency_hz));
    const std::string verdict = failed.empty() ? "pass" : fmt::format("FAIL ({})", fmt::join(failed, ", "));
    const ReferenceValue* reference = reference_at(design, check.frequency_hz);
    fmt::print("  {:>7g}  {:>7.4f}  {:>5}  {:>7}  {:>12.4f}  {:>7}  {}\n", check.frequency_hz, check.max_sensitivity,
               sensitivity_checked ? fmt::format("{:g}", control::kQftSensitivityBound) : std::string("-"),
               reference ? or_dash(reference->max_sensitivity) : "-", check.max_tracking_ratio,
               reference ? or_dash(reference->max_tracking_ratio) : "-", verdict);
  }
  if (violations.empty()) {
    fmt::print("  meets eq. 16 (|S| <= 0.4 up to 10 Hz) and eq. 17 (|T| <= |T_u|) at every design frequency\n\n");
  } else {
    fmt::print("  violates the bounds at {}\n\n", fmt::join(violations, ", "));
  }
}

std::vector<double> log_spaced_hz(double first, double last, std::size_t count) {
  std::vector<double> f(count);
  for (std::size_t i = 0; i < count; ++i) {
    f[i] = first * std::pow(last / first, static_cast<double>(i) / static_cast<double>(count - 1));
  }
  return f;
}

double decibel(double magnitude) { return 20.0 * std::log10(magnitude); }

constexpr const char* kFigureStyle =
    "set grid lc rgb '#dddddd' lw 1\n"
    "set border lc rgb '#444444'\n"
    "set key outside right top vertical box samplen 2 font ',10'\n";

// |S| and |T| (worst template point at each frequency) against |T_u| and the |S| bound.
Figure bode_figure(const CrossCouplingDesign& design, const control::TransferFunction& cross_coupling,
                   const fs::path& data_dir) {
  const control::CrossCouplingLoop loop = control::paper004_cross_coupling_loop();
  std::string dat = "# f_hz max_S_db max_T_db T_u_db (max: worst of the 21 template points)\n";
  for (const auto& check : control::check_qft_bounds(cross_coupling, loop, log_spaced_hz(0.1, 1000.0, 600))) {
    dat += fmt::format("{:.6g} {:.6f} {:.6f} {:.6f}\n", check.frequency_hz, decibel(check.max_sensitivity),
                       decibel(check.max_complementary), decibel(check.tracking_bound));
  }
  std::string design_points = "# f_hz max_S_db max_T_db at the design frequencies\n";
  for (const auto& check : control::check_qft_bounds(cross_coupling, loop)) {
    design_points += fmt::format("{:.6g} {:.6f} {:.6f}\n", check.frequency_hz, decibel(check.max_sensitivity),
                                 decibel(check.max_complementary));
  }
  const std::string stem = fmt::format("qft-{}-bode", design.flag_value);
  write_file_atomically((data_dir / (stem + ".dat")).string(), dat);
  write_file_atomically((data_dir / (stem + "-design.dat")).string(), design_points);
  Figure figure;
  figure.name = stem;
  figure.width_px = 1100;
  figure.body = std::string(kFigureStyle) + fmt::format(
      "set title '{title}: |S| and |T| (worst template point) vs the bounds' font ',12'\n"
      "set xlabel 'frequency [Hz]'\nset ylabel 'magnitude [dB]'\n"
      "set logscale x\nset format x '%g'\nset xrange [0.1:1000]\n"
      "set arrow from 0.1,{bound:.4f} to {bound_hz:g},{bound:.4f} nohead lw 2 dt 2 lc rgb '#2ca02c'\n"
      "plot 'data/{stem}.dat' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'max |S|', "
      "'data/{stem}.dat' using 1:3 with lines lw 2 lc rgb '#d62728' title 'max |T|', "
      "'data/{stem}.dat' using 1:4 with lines lw 2 dt 3 lc rgb '#444444' title '|T_u| (eq. 18)', "
      "NaN with lines lw 2 dt 2 lc rgb '#2ca02c' title '|S| = 0.4 (eq. 16)', "
      "'data/{stem}-design.dat' using 1:2 with points pt 7 ps 1 lc rgb '#1f77b4' title 'design frequencies', "
      "'data/{stem}-design.dat' using 1:3 with points pt 7 ps 1 lc rgb '#d62728' notitle\n",
      fmt::arg("title", gnuplot_text(design.title)), fmt::arg("stem", stem), fmt::arg("bound", decibel(control::kQftSensitivityBound)),
      fmt::arg("bound_hz", control::kQftSensitivityBoundMaxFrequencyHz));
  return figure;
}

// Open loop C K of each template point in the Nichols plane, with the |S| = 0.4 contour.
Figure nichols_figure(const CrossCouplingDesign& design, const control::TransferFunction& cross_coupling,
                      const fs::path& data_dir) {
  const control::CrossCouplingLoop loop = control::paper004_cross_coupling_loop();
  // The design frequencies join the sweep, so their markers sit on the curves' phase branch.
  const auto design_frequencies = control::qft_design_frequencies_hz();
  auto frequencies = log_spaced_hz(0.1, 1000.0, 1500);  // fine enough for the resonance loops
  frequencies.insert(frequencies.end(), design_frequencies.begin(), design_frequencies.end());
  std::sort(frequencies.begin(), frequencies.end());
  frequencies.erase(std::unique(frequencies.begin(), frequencies.end()), frequencies.end());
  std::string dat = "# phase_deg magnitude_db cx_squared f_hz (one block per template point)\n";
  std::string design_points = "# phase_deg magnitude_db cx_squared f_hz at the design frequencies\n";
  double lowest_phase = std::numeric_limits<double>::infinity();
  double highest_phase = -lowest_phase;
  for (const double cx2 : control::qft_template_cx_squared()) {
    double previous = std::numeric_limits<double>::quiet_NaN();
    const auto unwrapped_phase = [&previous](std::complex<double> value) {
      double phase = std::arg(value) * 180.0 / std::numbers::pi;
      if (!std::isnan(previous)) phase -= 360.0 * std::round((phase - previous) / 360.0);
      previous = phase;
      return phase;
    };
    for (const double f : frequencies) {
      const auto open_loop = control::contour_open_loop(cross_coupling, loop, cx2, 2.0 * std::numbers::pi * f);
      const double phase = unwrapped_phase(open_loop);
      lowest_phase = std::min(lowest_phase, phase);
      highest_phase = std::max(highest_phase, phase);
      const std::string row = fmt::format("{:.4f} {:.4f} {:.4f} {:.6g}\n", phase, decibel(std::abs(open_loop)), cx2, f);
      dat += row;
      if (std::find(design_frequencies.begin(), design_frequencies.end(), f) != design_frequencies.end()) {
        design_points += row;
      }
    }
    dat += "\n";
  }
  // |1/(1 + L)| = 0.4 <=> |1 + r e^{jθ}| = 2.5: r = -cos θ + sqrt(cos^2 θ + 5.25).
  std::string contour = "# phase_deg magnitude_db of |S| = 0.4\n";
  const double from = 360.0 * std::floor(lowest_phase / 360.0), to = 360.0 * std::ceil(highest_phase / 360.0);
  for (double theta = from; theta <= to + 1e-9; theta += 1.0) {
    const double c = std::cos(theta * std::numbers::pi / 180.0);
    const double inverse_bound = 1.0 / control::kQftSensitivityBound;
    contour += fmt::format("{:.1f} {:.4f}\n", theta, decibel(-c + std::sqrt(c * c + inverse_bound * inverse_bound - 1.0)));
  }
  const std::string stem = fmt::format("qft-{}-nichols", design.flag_value);
  write_file_atomically((data_dir / (stem + ".dat")).string(), dat);
  write_file_atomically((data_dir / (stem + "-design.dat")).string(), design_points);
  write_file_atomically((data_dir / (stem + "-bound.dat")).string(), contour);
  Figure figure;
  figure.name = stem;
  figure.width_px = 1100;
  figure.height_px = 750;
  figure.body = std::string(kFigureStyle) + fmt::format(
      "set title '{title}: open loop C K, 21 template points, 0.1 Hz - 1 kHz' font ',12'\n"
      "set xlabel 'phase [deg]'\nset ylabel 'magnitude [dB]'\n"
      "set palette defined (0 '#1f77b4', 1 '#d62728')\nset cblabel 'C_x^2 = sin^2 φ'\nset cbrange [0:1]\n"
      "set xtics 90\n"
      "set label 1 at -180,0 '' point pt 3 ps 2 lw 2 lc rgb '#000000' front\n"
      "plot 'data/{stem}.dat' using 1:2:3 with lines lw 1.5 lc palette notitle, "
      "'data/{stem}-bound.dat' using 1:2 with lines lw 2 dt 2 lc rgb '#2ca02c' title '|S| = 0.4 (eq. 16)', "
      "'data/{stem}-design.dat' using 1:2 with points pt 7 ps 0.6 lc rgb '#444444' title 'design frequencies', "
      "NaN with points pt 3 ps 2 lw 2 lc rgb '#000000' title 'critical point (-180 deg, 0 dB)'\n",
      fmt::arg("title", gnuplot_text(design.title)), fmt::arg("stem", stem));
  return figure;
}

}  // namespace

std::function<int()> add_qft_command(CLI::App& app) {
  struct Flags {
    std::string ccc = "eq20";
    std::string plot_dir;
    std::string plot_format = "png,svg";
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* qft = app.add_subcommand(
      "qft", "Check paper 004's QFT bounds for a cross-coupled contour controller C(s) (|S|, |T| vs |T_u|)");
  qft->add_option("--ccc", flags->ccc,
                  "Cross-coupling controllers, comma separated: eq20 (QFT design, default), eq19 (first try), "
                  "lpccc (eq. 13, Table 3: the PID-CCC with its low-pass, as in netmc sim)")
      ->type_name("NAME[,...]");
  qft->add_option("--plot", flags->plot_dir, "Write Bode and Nichols figures (PNG, SVG) into DIR")->type_name("DIR");
  qft->add_option("--plot-format", flags->plot_format, "Figure formats with --plot: png, svg or png,svg")
      ->type_name("FORMATS");
  return [flags]() -> int {
    const auto chosen = selected_designs(flags->ccc);
    const FigureFormats formats = parse_figure_formats(flags->plot_format, "--plot-format");
    if (!flags->plot_dir.empty()) {
      require_gnuplot();
      check_output_directory(flags->plot_dir, "--plot");
      try {
        gnuplot_quote(fs::absolute(flags->plot_dir).string());  // refused before anything is written
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string("--plot: ") + e.what());
      }
    }
    fmt::print("QFT bounds of paper 004 (section 3.2): worst of the 21 template points C_x = sin(phi), "
               "phi = 0:0.025pi:0.5pi,\nper design frequency; axis feedback G_c of eq. 2 with z_lp = 0.7 "
               "(assumed). Bounds: |S| <= 0.4 for f <= 10 Hz (eq. 16),\n|T|/|T_u| <= 1 (eqs. 17, 18). "
               "'ref': an independent check's value (the paper prints only the verdicts).\n\n");
    std::vector<Figure> figures;
    const fs::path data_dir = fs::path(flags->plot_dir) / "data";
    if (!flags->plot_dir.empty()) fs::create_directories(data_dir);
    for (const auto& design : chosen) {
      const control::TransferFunction cross_coupling = design.make();
      print_table(design, cross_coupling, control::check_qft_bounds(cross_coupling));
      if (!flags->plot_dir.empty()) {
        figures.push_back(bode_figure(design, cross_coupling, data_dir));
        figures.push_back(nichols_figure(design, cross_coupling, data_dir));
      }
    }
    if (!flags->plot_dir.empty()) {
      for (const auto& file : render_figures(figures, flags->plot_dir, formats, "qft")) fmt::print("wrote {}\n", file);
    }
    return 0;
  };
}

}  // namespace netmc::cli
