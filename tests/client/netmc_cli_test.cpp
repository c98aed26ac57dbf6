// The netmc binary end to end: exit codes, one clear message, no half-written output, JSON.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

namespace {

struct Result {
  int exit_code;
  std::string output;  // stdout and stderr
};

Result run(const std::string& arguments) {
  const std::string command = std::string(NETMC_BINARY) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::string output;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), static_cast<int>(buffer.size()), pipe)) output += buffer.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

std::filesystem::path scratch(const std::string& name) {
  auto path = std::filesystem::temp_directory_path() / ("netmc_cli_test_" + name);
  std::filesystem::remove_all(path);
  return path;
}

TEST(NetmcCli, BadInputFailsWithOneMessageNamingTheFieldAndWritesNothing) {
  const auto json = scratch("bad.json");
  const std::array<std::pair<const char*, const char*>, 14> cases{{
      {"--controller adrc+fuzzy", "controller: unknown name 'adrc+fuzzy'"},
      {"--trajectory circle:r=10,period", "--trajectory"},
      {"--sample-period 0", "--sample-period"},
      {"--sample-period -5ms", "--sample-period"},
      {"--adrc kp=nan", "--adrc kp"},
      {"--delay trace:/nonexistent/delays.csv", "/nonexistent/delays.csv"},
      {"--delay uniform:min=2ms,max=1ms", "downlink.delay"},
      {"--plant steam", "plant"},
      {"--iterations 0", "--iterations"},
      {"--compensate smith", "--compensate: expected none | predictor[:playout=D|bound] | packets[:horizon=N] | "
                              "predictor+packets[:horizon=N,playout=D|bound], got 'smith'"},
      {"--compensate packets:horizon=0", "--compensate: expected packets:horizon=N with N an integer of 2 to 64"},
      {"--compensate predictor+packets:horizon=65", "--compensate: expected predictor+packets:horizon=N with N an integer of 2 to 64"},
      {"--controller gtcf-adrc --compensate packets", "controller 'gtcf-adrc' cannot be copied"},
      {"--delay trace:ping.txt,rtt_share=2", "rtt_share: expected a number in (0, 1]"},
  }};
  for (const auto& [arguments, expected] : cases) {
    const Result result = run("sim " + std::string(arguments) + " --json " + json.string());
    EXPECT_NE(result.exit_code, 0) << arguments;
    EXPECT_NE(result.output.find(expected), std::string::npos) << arguments << "\n" << result.output;
    EXPECT_FALSE(std::filesystem::exists(json)) << arguments;
  }
}

// A real network's measurement replayed: `ping -D` output as --delay trace:FILE, half of each
// round trip by default, the whole with rtt_share=1.
TEST(NetmcCli, PingOutputReplaysAsADelayTrace) {
  const auto dir = scratch("ping-trace");
  std::filesystem::create_directories(dir);
  const auto ping = dir / "ping.txt";
  std::ofstream(ping) << "PING 127.0.0.1 (127.0.0.1) 56(84) bytes of data.\n"
                         "[1732780000.100000] 64 bytes from 127.0.0.1: icmp_seq=1 ttl=64 time=2.4 ms\n"
                         "[1732780001.100000] 64 bytes from 127.0.0.1: icmp_seq=2 ttl=64 time=6.0 ms\n"
                         "--- 127.0.0.1 ping statistics ---\n";
  for (const auto& [option, longest] : {std::pair{"", 0.003}, std::pair{",rtt_share=1", 0.006}}) {
    const auto json = dir / "run.json";
    std::filesystem::remove(json);
    const Result result = run("sim --controller adrc --iterations 1 --delay trace:" + ping.string() + option +
                              " --json " + json.string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    std::ifstream file(json);
    std::stringstream text;
    text << file.rdbuf();
    const std::string key = "\"tau_ca_max_s\": ";
    const auto at = text.str().find(key);
    ASSERT_NE(at, std::string::npos) << text.str();
    EXPECT_NEAR(std::stod(text.str().substr(at + key.size())), longest, 1e-9) << option;
  }
}

TEST(NetmcCli, UsageErrorsExitWithCode2) {
  EXPECT_EQ(run("sim --no-such-flag").exit_code, 2);
  EXPECT_EQ(run("sim --preset seed999").exit_code, 2);
  // Three-axis jobs have no planar figure: refused before anything runs.
  const auto figures = scratch("spatial");
  const Result plot = run("sim --preset thesis-spatial --plot " + figures.string());
  EXPECT_EQ(plot.exit_code, 2);
  EXPECT_NE(plot.output.find("--plot: the figures are planar"), std::string::npos) << plot.output;
  EXPECT_FALSE(std::filesystem::exists(figures));
}

// Single-axis runs (thesis ch. 5): the tracking error and the estimates are drawn, the planar
// contour figure is not; the trace has the x columns alone and the estimates after tau_x_s.
TEST(NetmcCli, SingleAxisRunsDrawTrackingErrorAndEstimates) {
  const auto figures = scratch("single-axis-figures");
  const Result result = run("sim --preset thesis-dead-zone --duration 0.2s --plot-format png --plot " + figures.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(std::filesystem::exists(figures / "contour_error.png"));
  EXPECT_TRUE(std::filesystem::exists(figures / "estimates-3.png"));  // C3: theta_hat and d_c
  EXPECT_FALSE(std::filesystem::exists(figures / "contour.png"));
  std::ifstream file(figures / "traces" / "3-C3_I.csv");
  ASSERT_TRUE(file) << "no trace of C3";
  std::string header;
  std::getline(file, header);
  EXPECT_EQ(header,
            "time_s,x_ref_m,x_m,x_measured_m,contour_error_m,contour_error_estimate_m,ux,Ux,ue,tau_x_s,"
            "B_hat[1/s],A_hat[m/s^2],mr_hat[m/s^2/V],mrbr_hat[m/s^2],ml_hat[m/s^2/V],mlbl_hat[m/s^2],dc_hat[m/s^2]");
}

TEST(NetmcCli, ThreeAxisTracesHaveAColumnPerAxis) {
  const auto traces = scratch("spatial-traces");
  const Result result = run("sim --preset thesis-spatial --duration 0.1s --csv " + traces.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream file(traces / "1-gtcf-sarc__3_axes.csv");
  ASSERT_TRUE(file) << "no trace of the first run";
  std::string header, first_row;
  std::getline(file, header);
  std::getline(file, first_row);
  EXPECT_EQ(header,
            "time_s,x_ref_m,y_ref_m,z_ref_m,x_m,y_m,z_m,x_measured_m,y_measured_m,z_measured_m,"
            "contour_error_m,contour_error_estimate_m,ux,uy,uz,Ux,Uy,Uz,ue,tau_x_s");
  EXPECT_EQ(std::count(first_row.begin(), first_row.end(), ','), std::count(header.begin(), header.end(), ','));
  std::size_t rows = 1;
  for (std::string line; std::getline(file, line);) ++rows;
  EXPECT_EQ(rows, 501u);  // 0.1 s at 0.2 ms, samples 0..N
}

TEST(NetmcCli, AdaptiveControllersWriteTheirEstimatesToTracesAndJson) {
  const auto traces = scratch("estimate-traces");
  const auto json = scratch("estimates.json");
  const Result result = run("sim --preset thesis-darc --controller gtcf-darc --duration 0.05s --csv " +
                            traces.string() + " --json " + json.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream file(traces / "1-gtcf-darc.csv");
  std::string header;
  std::getline(file, header);
  EXPECT_NE(header.find(",ue,tau_x_s,M1_hat[V/(m/s^2)],M2_hat[V/(m/s^2)],B1_hat[V/(m/s)]"), std::string::npos)
      << header;
  EXPECT_NE(header.find("dn2_hat[V]"), std::string::npos);
  std::ifstream results(json);
  const std::string text((std::istreambuf_iterator<char>(results)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find(R"json("name": "M1_hat",)json"), std::string::npos) << text;
  EXPECT_NE(text.find(R"json("unit": "V/(m/s^2)",)json"), std::string::npos) << text;
  EXPECT_NE(text.find(R"json("estimates": [)json"), std::string::npos) << text;
}

TEST(NetmcCli, JsonHoldsEveryIterationOfEveryRun) {
  const auto json = scratch("out.json");
  const auto csv = scratch("traces");
  const Result result = run("sim --controller adrc,adrc+ilccc --iterations 3 --json " +
                            json.string() + " --csv " + csv.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream file(json);
  std::stringstream content;
  content << file.rdbuf();
  const std::string text = content.str();
  for (const char* key : {"\"runs\"", "\"controller\": \"adrc+ilccc\"", "\"iterations\"",
                          "\"iteration\": 3", "\"e_max_m\"", "\"e_rms_m\"", "\"e_sum_m\"",
                          "\"tau_mean_s\"", "\"tau_max_s\"", "\"plant\": \"seed001\"",
                          "\"trajectory\"", "\"delay\""}) {
    EXPECT_NE(text.find(key), std::string::npos) << key;
  }
  EXPECT_TRUE(std::filesystem::exists(csv / "2-adrc_ilccc.csv"));
  EXPECT_NE(result.output.find("adrc+ilccc"), std::string::npos);
  std::filesystem::remove_all(json);
  std::filesystem::remove_all(csv);
}

TEST(NetmcCli, FailOnUnstableExitsWith3NamingTheRunsAndStillWritesTheResults) {
  const auto json = scratch("unstable.json");
  // Constant 20 ms: both runs diverge in iteration 1 (docs/user-guide/delay-compensation.md).
  const std::string unstable = "sim --controller adrc,adrc+pidccc --iterations 1 --delay constant:20ms";
  const Result failing = run(unstable + " --fail-on-unstable --json " + json.string());
  EXPECT_EQ(failing.exit_code, 3) << failing.output;
  EXPECT_NE(failing.output.find("netmc: 2 of 2 runs gave no result (unstable or did not follow): adrc, adrc+pidccc"),
            std::string::npos)
      << failing.output;
  EXPECT_TRUE(std::filesystem::exists(json));
  EXPECT_EQ(run(unstable).exit_code, 0);  // without the flag: the table says it, the exit code not
  EXPECT_EQ(run("sim --controller adrc --iterations 1 --fail-on-unstable").exit_code, 0);
  std::filesystem::remove_all(json);
}

TEST(NetmcCli, JsonSpecFileRunsAndBadSpecNamesTheFile) {
  const auto spec = scratch("spec.json");
  {
    std::ofstream out(spec);
    out << R"({"trajectory": {"line": {"x0_m": 0, "y0_m": 0, "x1_m": 0.02, "y1_m": 0.01,
              "duration_s": 2}}, "controller": {"name": "adrc+pidccc"}, "iterations": 2})";
  }
  const Result ok = run("sim --spec " + spec.string());
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("adrc+pidccc"), std::string::npos);
  {
    std::ofstream out(spec);
    out << R"({"iterations": "many"})";
  }
  const Result bad = run("sim --spec " + spec.string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find(spec.string()), std::string::npos) << bad.output;
  std::filesystem::remove(spec);
}

TEST(NetmcCli, SpecLargerThanItsBoundIsRefusedWithoutReadingItAll) {
  // /dev/zero never ends: read whole, it would fill memory.
  const Result endless = run("sim --spec /dev/zero");
  EXPECT_EQ(endless.exit_code, 2);
  EXPECT_NE(endless.output.find("--spec: '/dev/zero' is larger than 4 MiB"), std::string::npos) << endless.output;
}

}  // namespace
