// Figures: a tiny study and a tiny sweep rendered by gnuplot into non-empty PNG and SVG files;
// a failing gnuplot leaves no figure behind and says why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tests/client/netmc_in_process.hpp"
#include "client/gnuplot.hpp"
#include "client/study_report.hpp"

namespace netmc::cli {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const auto path = fs::temp_directory_path() / ("netmc_plot_test_" + name);
  fs::remove_all(path);
  return path;
}

int netmc(const std::vector<std::string>& arguments) { return run_netmc_captured(arguments).exit_code; }

std::string head(const fs::path& path, std::size_t bytes) {
  std::ifstream file(path, std::ios::binary);
  std::string text(bytes, '\0');
  file.read(text.data(), static_cast<std::streamsize>(bytes));
  text.resize(static_cast<std::size_t>(file.gcount()));
  return text;
}

// Temporaries of figures (NAME.png.XXXXXX, NAME.svg.XXXXXX) left in a directory.
std::string read_text(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

int leftovers(const fs::path& dir) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    for (const char* kind : {".png.", ".svg."}) {
      const auto at = name.find(kind);
      if (at != std::string::npos && name.size() == at + 5 + 6) ++count;
    }
  }
  return count;
}

void expect_figure(const fs::path& dir, const std::string& name) {
  const auto png = dir / (name + ".png");
  const auto svg = dir / (name + ".svg");
  ASSERT_TRUE(fs::exists(png)) << png;
  ASSERT_TRUE(fs::exists(svg)) << svg;
  EXPECT_GT(fs::file_size(png), 5000u) << png;   // a drawn figure, not an empty canvas
  EXPECT_GT(fs::file_size(svg), 5000u) << svg;
  EXPECT_EQ(head(png, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << png;
  EXPECT_NE(head(svg, 400).find("<svg"), std::string::npos) << svg;
  EXPECT_EQ(leftovers(dir), 0) << dir;
}

TEST(PlotRender, SimPlotDrawsTheStandardFigures) {
  if (!find_gnuplot()) GTEST_SKIP() << "gnuplot is not installed (Debian package gnuplot-nox)";
  const auto dir = scratch("sim");
  ASSERT_EQ(netmc({"sim", "--controller", "adrc,adrc+ilccc", "--iterations", "3", "--duration", "1s",
                   "--plot", dir.string(), "-q"}),
            0);
  for (const char* name : {"contour", "contour_error", "e_sum", "tau_histogram"}) expect_figure(dir, name);
  EXPECT_TRUE(fs::exists(dir / "results.json"));
  EXPECT_TRUE(fs::exists(dir / "traces" / "2-adrc_ilccc.csv"));
  // The kept script names its data and figures relative to the figure directory: moved
  // elsewhere, the directory redraws in place.
  const std::string kept = read_text(dir / "data" / "sim.gp");
  const std::string comment = "#   cd " + dir.string();
  EXPECT_EQ(kept.find(dir.string()), kept.find(comment) + comment.size() - dir.string().size()) << kept;  // only in the comment
  EXPECT_EQ(kept.find(".partial"), std::string::npos);
  EXPECT_NE(kept.find("set output 'contour.png'"), std::string::npos);
  EXPECT_NE(kept.find("'data/contour-1.dat'"), std::string::npos);
  EXPECT_EQ(kept.rfind(dir.string()), kept.find(dir.string()));
  for (const auto& entry : fs::directory_iterator(dir / "data")) {  // the script run is not kept
    EXPECT_NE(entry.path().filename().string().rfind("sim.gp.", 0), 0u) << entry.path();
  }
  // Moved, the directory redraws itself with its kept script.
  const auto moved = scratch("sim_moved");
  fs::copy(dir, moved, fs::copy_options::recursive);
  fs::remove(moved / "contour.png");
  const std::string redraw = "cd '" + moved.string() + "' && " + *find_gnuplot() + " data/sim.gp";
  EXPECT_EQ(std::system(redraw.c_str()), 0) << redraw;
  EXPECT_GT(fs::file_size(moved / "contour.png"), 5000u);
  fs::remove_all(moved);

  // netmc plot --sim redraws from the saved outputs alone.
  const auto again = scratch("sim_again");
  fs::remove(dir / "contour.png");
  ASSERT_EQ(netmc({"plot", "--sim", dir.string(), "--out", again.string(), "--format", "png"}), 0);
  EXPECT_TRUE(fs::exists(again / "contour.png"));
  EXPECT_FALSE(fs::exists(again / "contour.svg"));
  fs::remove_all(dir);
  fs::remove_all(again);
}

// Double of a data file's first data row's first column (after the # header).
double first_value(const fs::path& path) {
  std::ifstream file(path);
  std::string line;
  while (std::getline(file, line) && line.starts_with('#')) {
  }
  return std::stod(line);
}

double max_abs_second_column(const fs::path& path) {
  std::ifstream file(path);
  std::string line;
  double max = 0.0;
  while (std::getline(file, line)) {
    if (line.starts_with('#')) continue;
    std::istringstream row(line);
    double time = 0.0, value = 0.0;
    row >> time >> value;
    max = std::max(max, std::abs(value));
  }
  return max;
}

// A study judged after its start-up transient (thesis presets): the error figure and the zoom
// cover the evaluation window, so the peak they show is the steady maximum of the table.
TEST(PlotRender, SteadyStudyFiguresShowTheEvaluationWindow) {
  if (!find_gnuplot()) GTEST_SKIP() << "gnuplot is not installed (Debian package gnuplot-nox)";
  const auto dir = scratch("steady");
  const auto json_path = fs::temp_directory_path() / "netmc_plot_test_steady.json";
  ASSERT_EQ(netmc({"sim", "--preset", "thesis-ellipse", "--controller", "gtcf-sarc", "--duration", "11s",
                   "--plot", dir.string(), "--json", json_path.string(), "-q"}),
            0);
  EXPECT_NEAR(first_value(dir / "data" / "contour_error-1.dat"), 10.0, 2e-4);  // the preset's window
  std::ifstream json(json_path);
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  const auto at = text.find("\"e_max_steady_m\":");
  ASSERT_NE(at, std::string::npos);
  const double e_max_steady_um = std::stod(text.substr(at + 17)) * 1e6;
  EXPECT_GT(e_max_steady_um, 0.5);
  EXPECT_NEAR(max_abs_second_column(dir / "data" / "contour_error-1.dat"), e_max_steady_um, 0.01);
  fs::remove_all(dir);
  fs::remove(json_path);
}

TEST(PlotRender, SweepPlotDrawsMetricVsDelay) {
  if (!find_gnuplot()) GTEST_SKIP() << "gnuplot is not installed (Debian package gnuplot-nox)";
  const auto dir = scratch("sweep");
  fs::create_directories(dir);
  const auto csv = (dir / "sweep.csv").string();
  ASSERT_EQ(netmc({"sweep", "--controller", "adrc,adrc+pidccc", "--delay-max", "1ms:5ms:3", "--seeds",
                   "1..2", "--iterations", "2", "--duration", "0.5s", "--csv", csv, "-q"}),
            0);
  ASSERT_EQ(netmc({"plot", "--sweep", csv, "--metric", "e_max_m,tau_p99_s"}), 0);
  expect_figure(dir, "sweep-e_max_m");
  expect_figure(dir, "sweep-tau_p99_s");
  // The axis states the delays' lower bound, paper 001's 0.3 ms (sweep's default --delay-min).
  EXPECT_NE(read_text(dir / "data" / "sweep.gp").find("(each delay uniform from 300 us up to it)"), std::string::npos);
  fs::remove_all(dir);
}

TEST(PlotRender, FailingGnuplotLeavesNoFigureAndSaysWhy) {
  const auto dir = scratch("failing");
  setenv("NETMC_GNUPLOT", "/bin/false", 1);
  Figure figure;
  figure.name = "empty";
  figure.body = "plot x";
  try {
    render_figures({figure}, dir.string(), {});
    ADD_FAILURE() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("gnuplot failed (exit 1)"), std::string::npos) << error.what();
  }
  unsetenv("NETMC_GNUPLOT");
  EXPECT_FALSE(fs::exists(dir / "empty.png"));
  EXPECT_EQ(leftovers(dir), 0);
  fs::remove_all(dir);
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << text;
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
}

// gnuplot runs backquoted text as a shell command anywhere but inside single quotes. A run label
// from a spec file, a results.json or a sweep CSV with a planted command must be drawn as text.
TEST(PlotRender, HostileLabelsAreDrawnAsTextNeverRun) {
  if (!find_gnuplot()) GTEST_SKIP() << "gnuplot is not installed (Debian package gnuplot-nox)";
  const auto dir = scratch("hostile");
  fs::create_directories(dir);
  const auto marker = [&](int i) { return dir / ("ran-" + std::to_string(i)); };
  // 1. netmc sim --spec with a hostile name (command, both quotes, markup, a line break), --plot.
  const auto spec = dir / "evil.json";
  write_text(spec, R"({"name": "x`touch )" + marker(1).string() +
                       R"(`\" ' @{_^&~\\} \nset output", "duration_s": 0.5,
                       "trajectory": {"circle": {"radius_m": 0.01, "center_x_m": 0.05, "center_y_m": 0.05, "period_s": 8}}})");
  const auto sim_dir = dir / "sim";
  ASSERT_EQ(netmc({"sim", "--spec", spec.string(), "--plot", sim_dir.string(), "-q"}), 0);
  expect_figure(sim_dir, "contour");
  EXPECT_FALSE(fs::exists(marker(1)));
  EXPECT_EQ(read_text(sim_dir / "data" / "sim.gp").find('`'), std::string::npos);

  // 2. netmc plot --sim with a results.json whose label was edited.
  std::string results = read_text(sim_dir / "results.json");
  const std::string key = R"("label": ")";
  const auto label_at = results.find(key);
  ASSERT_NE(label_at, std::string::npos);
  const auto start = label_at + key.size();
  const auto end = results.find("\",\n", start);  // the label holds an escaped quote itself
  const std::string hostile = "`touch " + marker(2).string() + "`";
  results.replace(start, end - start, hostile);
  write_text(sim_dir / "results.json", results);
  // The run's trace under the name the edited label gives it (the only trace there).
  fs::path trace;
  for (const auto& entry : fs::directory_iterator(sim_dir / "traces")) trace = entry.path();
  fs::rename(trace, sim_dir / "traces" / trace_file_name(0, hostile));
  ASSERT_EQ(netmc({"plot", "--sim", sim_dir.string(), "--out", (dir / "again").string(), "--format", "png"}), 0);
  EXPECT_FALSE(fs::exists(marker(2)));

  // 3. netmc plot --sweep with a run column carrying a command.
  const auto csv = dir / "sweep.csv";
  ASSERT_EQ(netmc({"sweep", "--controller", "adrc", "--delay-max", "1ms:2ms:2", "--seeds", "1", "--iterations",
                   "1", "--duration", "0.5s", "--csv", csv.string(), "-q"}),
            0);
  std::string table = read_text(csv);
  replace_all(table, ",adrc,", ",`touch " + marker(3).string() + "`,");
  write_text(csv, table);
  ASSERT_EQ(netmc({"plot", "--sweep", csv.string(), "--metric", "e_max_m"}), 0);
  expect_figure(dir, "sweep-e_max_m");
  EXPECT_FALSE(fs::exists(marker(3)));
  // A metric name is a column name, not a path or a label to interpret.
  EXPECT_NE(netmc({"plot", "--sweep", csv.string(), "--metric", "../e_max_m"}), 0);
  fs::remove_all(dir);
}

TEST(Gnuplot, TextCannotLeaveItsStringAndPathsWithLineBreaksAreRefused) {
  EXPECT_EQ(gnuplot_text("a`b`'c\nd_e"), "a\xE2\x80\x99" "b\xE2\x80\x99\xE2\x80\x99" R"(c d\_e)");
  EXPECT_EQ(gnuplot_quote("/tmp/figures"), "'/tmp/figures'");
  EXPECT_THROW(gnuplot_quote("/tmp/it's"), std::invalid_argument);
  EXPECT_THROW(gnuplot_quote("/tmp/a\nset output"), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::cli

#include "client/figures.hpp"
#include "control/controller_estimate.hpp"

namespace netmc::cli {
namespace {

// A trace file is input: its estimate columns become at most kMaxControllerEstimates panels,
// and their names reach gnuplot only as text.
TEST(PlotRender, EstimateFiguresAreBoundedAndQuoteTheirNames) {
  std::string header = "time_s,x_ref_m,y_ref_m,x_m,y_m,contour_error_m,tau_x_s";
  std::string row = "0,0,0,0,0,0,0";
  for (int i = 0; i < 100; ++i) {
    header += ",e`touch x`" + std::to_string(i) + "[V]";
    row += ",1";
  }
  SimOutputs outputs;
  outputs.study.add_runs()->set_label("run");
  outputs.traces.push_back({"run", CsvTable::parse(header + "\n" + row + "\n" + row + "\n", "trace.csv")});
  const auto dir = std::filesystem::temp_directory_path() / "netmc-estimate-figure-test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto figures = sim_figures(outputs, dir.string());
  std::filesystem::remove_all(dir);
  const auto estimates = std::find_if(figures.begin(), figures.end(), [](const Figure& f) { return f.name == "estimates-1"; });
  ASSERT_NE(estimates, figures.end());
  std::size_t plots = 0;
  for (std::size_t at = estimates->body.find("\nplot "); at != std::string::npos; at = estimates->body.find("\nplot ", at + 1)) ++plots;
  EXPECT_EQ(plots, control::kMaxControllerEstimates);
  EXPECT_EQ(estimates->body.find('`'), std::string::npos);  // backquotes would run a shell
}

}  // namespace
}  // namespace netmc::cli
