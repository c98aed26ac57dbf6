// `netmc qft` in-process: the printed eq. 20 table against an independent check's numbers, the
// verdicts of eq. 19 and the PID-CCC, a bad --ccc value, and the Bode and Nichols figures.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "client/gnuplot.hpp"
#include "tests/client/netmc_in_process.hpp"

namespace netmc::cli {
namespace {

namespace fs = std::filesystem;

struct Row {
  double max_sensitivity;
  double max_tracking_ratio;
  std::string verdict;
};

// The rows of the table under the heading that starts with `heading`, by frequency.
std::map<double, Row> table_rows(const std::string& out, const std::string& heading) {
  std::map<double, Row> rows;
  const auto start = out.find(heading);
  if (start == std::string::npos) return rows;
  std::istringstream lines(out.substr(start));
  std::string line;
  std::getline(lines, line);  // the heading
  while (std::getline(lines, line) && !line.empty()) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    // f, max|S|, bound, ref, max|T|/|T_u|, ref, verdict...
    if (w.size() < 7) continue;
    try {
      std::size_t used = 0;
      const double f = std::stod(w[0], &used);
      if (used != w[0].size()) continue;
      std::string verdict = w[6];
      for (std::size_t i = 7; i < w.size(); ++i) verdict += " " + w[i];
      rows[f] = {std::stod(w[1]), std::stod(w[4]), verdict};
    } catch (const std::invalid_argument&) {
      continue;  // the column titles and the C(s) line
    }
  }
  return rows;
}

TEST(NetmcQft, Eq20TableReproducesTheReferenceCheck) {
  const NetmcOutcome result = run_netmc_captured({"qft"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto rows = table_rows(result.out, "paper 004, eq. 20");
  ASSERT_EQ(rows.size(), 7u) << result.out;
  // The independent check: max|S| 0.10 (0.1-1 Hz, to two decimals), 0.215 (10 Hz), 0.71 (35 Hz).
  EXPECT_NEAR(rows.at(0.1).max_sensitivity, 0.10, 0.002) << result.out;
  EXPECT_NEAR(rows.at(0.5).max_sensitivity, 0.10, 0.002) << result.out;
  EXPECT_NEAR(rows.at(1.0).max_sensitivity, 0.10, 0.005) << result.out;
  EXPECT_NEAR(rows.at(10.0).max_sensitivity, 0.215, 0.02 * 0.215) << result.out;
  EXPECT_NEAR(rows.at(35.0).max_sensitivity, 0.71, 0.02 * 0.71) << result.out;
  for (const auto& [f, row] : rows) {
    EXPECT_LE(row.max_tracking_ratio, 0.917 * 1.02) << f;
    EXPECT_EQ(row.verdict, "pass") << f;
  }
  EXPECT_NE(result.out.find("meets eq. 16"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("<=0.917"), std::string::npos) << "the reference value beside the measured one";
}

TEST(NetmcQft, Eq19FailsAt35HzAndThePidCrossCouplingAt10Hz) {
  const NetmcOutcome result = run_netmc_captured({"qft", "--ccc", "eq19,lpccc"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out.find("eq. 20"), std::string::npos) << "only the chosen controllers";
  const auto eq19 = table_rows(result.out, "paper 004, eq. 19");
  ASSERT_EQ(eq19.size(), 7u) << result.out;
  EXPECT_NEAR(eq19.at(35.0).max_tracking_ratio, 1.056, 0.02 * 1.056);
  EXPECT_EQ(eq19.at(35.0).verdict, "FAIL (eq. 17)");
  const auto pid = table_rows(result.out, "paper 004, eq. 13");
  ASSERT_EQ(pid.size(), 7u) << result.out;
  EXPECT_NEAR(pid.at(10.0).max_sensitivity, 0.53, 0.02 * 0.53);
  EXPECT_EQ(pid.at(10.0).verdict.rfind("FAIL (eq. 16", 0), 0u) << pid.at(10.0).verdict;
}

TEST(NetmcQft, BadControllerNameExitsWith2NamingTheFlag) {
  for (const char* value : {"eq21", "eq20,fuzzy", ","}) {
    const NetmcOutcome result = run_netmc_captured({"qft", "--ccc", value});
    EXPECT_EQ(result.exit_code, 2) << value;
    EXPECT_EQ(result.err.rfind("netmc: error: --ccc: ", 0), 0u) << value << "\n" << result.err;
    EXPECT_NE(result.err.find("eq20, eq19 or lpccc"), std::string::npos) << result.err;
    EXPECT_EQ(result.out, "") << value;
  }
  const NetmcOutcome help = run_netmc_captured({"qft", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("Examples:"), std::string::npos);
  EXPECT_NE(help.out.find("netmc qft --ccc"), std::string::npos);
}

TEST(NetmcQft, PlotWritesBodeAndNicholsFigures) {
  if (!find_gnuplot()) GTEST_SKIP() << "gnuplot is not installed (Debian package gnuplot-nox)";
  const auto dir = fs::temp_directory_path() / "netmc_qft_test_figures";
  fs::remove_all(dir);
  const NetmcOutcome result = run_netmc_captured({"qft", "--ccc", "eq20,lpccc", "--plot", dir.string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  for (const char* name : {"qft-eq20-bode", "qft-eq20-nichols", "qft-lpccc-bode", "qft-lpccc-nichols"}) {
    for (const char* extension : {".png", ".svg"}) {
      const auto file = dir / (std::string(name) + extension);
      ASSERT_TRUE(fs::exists(file)) << file;
      EXPECT_GT(fs::file_size(file), 1000u) << file;
    }
  }
  EXPECT_TRUE(fs::exists(dir / "data" / "qft.gp"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace netmc::cli
