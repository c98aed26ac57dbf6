// The netmc command line in-process: every bad value of the sweep, plot and output flags ends
// with exit code 2 and one message line naming the flag; help has examples.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/client/netmc_in_process.hpp"

namespace netmc::cli {
namespace {

using Outcome = NetmcOutcome;

Outcome netmc(const std::vector<std::string>& arguments) { return run_netmc_captured(arguments); }

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream stream(text);
  for (std::string word; stream >> word;) out.push_back(word);
  return out;
}

TEST(NetmcUsage, EveryBadValueOfANewFlagExitsWith2AndOneMessageNamingIt) {
  const auto missing = (std::filesystem::temp_directory_path() / "netmc_no_such_dir" / "x.csv").string();
  const std::vector<std::pair<std::string, std::string>> cases{
      {"sweep --delay-max 1ms:2ms", "--delay-max: expected START:STOP:COUNT"},
      {"sweep --delay-max 5ms:1ms:3", "--delay-max: expected STOP above START"},
      {"sweep --delay-max 1ms:2ms:0", "--delay-max COUNT"},
      {"sweep --delay-max fast", "--delay-max: expected a duration"},
      {"sweep --delay-max 0.1ms", "--delay-max: every value must be at least --delay-min"},
      {"sweep --delay-max 2ms --delay-min soon", "--delay-min: expected a duration"},
      {"sweep --delay-min 1ms", "--delay-min: only meaningful with --delay-max"},
      {"sweep --delay warp:9", "--delay: unknown delay 'warp'"},
      {"sweep --seeds 9..2", "--seeds: expected FIRST..LAST"},
      {"sweep --seeds one", "--seeds: expected FIRST..LAST"},
      {"sweep --threads 0", "--threads"},
      {"sweep --preset seed999", "--preset: unknown name 'seed999'"},
      {"sweep --preset ,", "--preset: expected NAME"},
      {"sweep --controller adrc+fuzzy", "controller: unknown name 'adrc+fuzzy'"},
      {"sweep --iterations 0", "--iterations"},
      {"sweep --csv " + missing, "--csv: directory"},
      {"sweep --json " + missing, "--json: directory"},
      {"sweep --no-such-flag", "--no-such-flag"},
      {"plot", "plot: expected --sim DIR or --sweep FILE.csv"},
      {"plot --sweep " + missing, missing + ": cannot read"},
      {"plot --sim " + missing, "results.json: cannot read"},
      {"plot --sweep x.csv --sim y", "--sim excludes --sweep"},
      {"plot --sweep x.csv --format gif", "--format: expected png, svg or png,svg"},
      {"sim --plot-format jpeg --plot out", "--plot-format: expected png, svg or png,svg"},
      {"sim --threads 0", "--threads"},
      {"sim --quiet --verbose", "--quiet excludes --verbose"},
      {"--quiet sim --verbose", "--quiet: cannot be combined with --verbose"},
  };
  for (const auto& [arguments, expected] : cases) {
    const Outcome result = netmc(words(arguments));
    EXPECT_EQ(result.exit_code, 2) << arguments << "\n" << result.err;
    EXPECT_NE(result.err.find(expected), std::string::npos) << arguments << "\n" << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << arguments << "\n" << result.err;
    EXPECT_EQ(result.err.rfind("netmc: error: ", 0), 0u) << arguments << "\n" << result.err;
  }
}

TEST(NetmcUsage, SpecFileErrorsNameTheFileAndTheField) {
  const auto spec = (std::filesystem::temp_directory_path() / "netmc_usage_spec.json").string();
  const std::vector<std::pair<std::string, std::string>> cases{
      {R"({"controller": {"adrc": {"w0": -3}}})", spec + ": controller.gains.adrc.w0: expected a positive finite number, got -3"},
      {R"({"controller": {"name": "adrc+fuzzy"}})", spec + ": controller: unknown name 'adrc+fuzzy'"},
      {R"({"plant": "steam"})", spec + ": plant: "},
      {R"({"controller": {"adrc": {"observer": "rk4"}}})", spec + ": controller.gains.adrc.observer: expected euler or zoh, got 'rk4'"},
  };
  for (const auto& [json, expected] : cases) {
    {
      std::ofstream file(spec);
      // A complete job apart from the one mistake.
      file << R"({"trajectory": {"line": {"x1_m": 0.01, "duration_s": 0.5}}, )" << json.substr(1);
    }
    for (const char* subcommand : {"sim", "sweep"}) {
      const Outcome result = netmc({subcommand, "--spec", spec});
      EXPECT_EQ(result.exit_code, 2) << subcommand << " " << json;
      EXPECT_NE(result.err.find("netmc: error: " + expected), std::string::npos) << json << "\n" << result.err;
    }
  }
  std::filesystem::remove(spec);
}

TEST(NetmcUsage, HelpOfEverySubcommandHasExamples) {
  for (const char* subcommand : {"sim", "sweep", "plot", "run", "nodes", "cee"}) {
    const Outcome result = netmc({subcommand, "--help"});
    EXPECT_EQ(result.exit_code, 0) << subcommand;
    EXPECT_NE(result.out.find("Examples:"), std::string::npos) << subcommand;
    EXPECT_NE(result.out.find(std::string("netmc ") + subcommand), std::string::npos) << subcommand;
    EXPECT_NE(result.out.find("--quiet"), std::string::npos) << subcommand;
    EXPECT_NE(result.out.find("--verbose"), std::string::npos) << subcommand;
  }
  const Outcome top = netmc({"--help"});
  EXPECT_EQ(top.exit_code, 0);
  for (const char* text : {"Examples:", "sweep", "plot", "Exit codes"}) {
    EXPECT_NE(top.out.find(text), std::string::npos) << text;
  }
}

TEST(NetmcUsage, QuietSweepPrintsNothingOnStderrAndVerboseLogsAtInfo) {
  const std::vector<std::string> grid{"sweep", "--controller", "adrc", "--duration", "0.2s",
                                      "--iterations", "2", "--seeds", "1..2"};
  auto quiet_arguments = grid;
  quiet_arguments.push_back("--quiet");
  const Outcome quiet = netmc(quiet_arguments);
  EXPECT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  EXPECT_NE(quiet.out.find("2 configurations, 4 iterations run"), std::string::npos) << quiet.out;

  const Outcome normal = netmc(grid);  // stderr is not a terminal here: plain progress lines
  EXPECT_NE(normal.err.find("progress: 100%"), std::string::npos) << normal.err;
  EXPECT_EQ(normal.err.find("info"), std::string::npos) << normal.err;

  auto verbose_arguments = grid;
  verbose_arguments.push_back("-v");
  const Outcome verbose = netmc(verbose_arguments);
  EXPECT_NE(verbose.err.find("netmc: info: sweep: 2 configurations, 4 iterations in all"), std::string::npos)
      << verbose.err;
}

}  // namespace
}  // namespace netmc::cli
