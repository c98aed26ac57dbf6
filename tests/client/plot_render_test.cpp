// Figures: a tiny study and a tiny sweep rendered by gnuplot into non-empty PNG and SVG files;
// a failing gnuplot leaves no figure behind and says why.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/client/netmc_in_process.hpp"
#include "client/gnuplot.hpp"

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

void expect_figure(const fs::path& dir, const std::string& name) {
  const auto png = dir / (name + ".png");
  const auto svg = dir / (name + ".svg");
  ASSERT_TRUE(fs::exists(png)) << png;
  ASSERT_TRUE(fs::exists(svg)) << svg;
  EXPECT_GT(fs::file_size(png), 5000u) << png;   // a drawn figure, not an empty canvas
  EXPECT_GT(fs::file_size(svg), 5000u) << svg;
  EXPECT_EQ(head(png, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << png;
  EXPECT_NE(head(svg, 400).find("<svg"), std::string::npos) << svg;
  EXPECT_FALSE(fs::exists(dir / (name + ".png.partial")));
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
  EXPECT_TRUE(fs::exists(dir / "data" / "figures.gp"));

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
  EXPECT_FALSE(fs::exists(dir / "empty.png.partial"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace netmc::cli
