#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "netsim/delay_model.hpp"
#include "netsim_test_support.hpp"

namespace netmc::netsim {
namespace {

using test::expect_invalid_argument;

const std::string kDataDir = NETMC_TEST_DATA_DIR;

// A CSV file in the temp directory, named after the running test, removed afterwards.
class TempCsv {
 public:
  explicit TempCsv(const std::string& content) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("netmc_netsim_" + std::string(info->name()) + "_" + std::to_string(counter_++) + ".csv");
    std::ofstream(path_, std::ios::binary) << content;
  }
  ~TempCsv() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  TempCsv(const TempCsv&) = delete;
  TempCsv& operator=(const TempCsv&) = delete;
  std::string path() const { return path_.string(); }

 private:
  static inline int counter_ = 0;
  std::filesystem::path path_;
};

void expect_delays(const std::vector<double>& actual, const std::vector<double>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_DOUBLE_EQ(actual[i], expected[i]) << "sample " << i;
}

TEST(DelayTraceCsv, MillisecondFixtureWithCommentsHeaderAndBlankLines) {
  expect_delays(load_delay_trace_csv(kDataDir + "/delay_trace_ms.csv"), {1.5e-3, 2.25e-3, 0.5e-3, 10e-3});
}

TEST(DelayTraceCsv, SecondsFixtureWithoutHeader) {
  expect_delays(load_delay_trace_csv(kDataDir + "/delay_trace_s.csv"), {0.001, 0.0025, 0.0004});
}

TEST(DelayTraceCsv, HeaderSuffixSetsUnit) {
  TempCsv microseconds("t,delay_us\n0,250\n1,1e3\n");
  expect_delays(load_delay_trace_csv(microseconds.path()), {250e-6, 1e-3});
  TempCsv seconds("\"delay_s\"\n0.5\n");
  expect_delays(load_delay_trace_csv(seconds.path()), {0.5});
  TempCsv unknown_suffix("cycle,delay\n0,0.002\n");
  expect_delays(load_delay_trace_csv(unknown_suffix.path()), {0.002});
  TempCsv upper_case("CYCLE,DELAY_MS\n0,2\n");
  expect_delays(load_delay_trace_csv(upper_case.path()), {0.002});
}

TEST(DelayTraceCsv, HandlesCrlfWhitespaceAndPlusSign) {
  TempCsv file("delay_ms\r\n  # indented comment\r\n 1.0 \r\n+2\r\n\r\n");
  expect_delays(load_delay_trace_csv(file.path()), {1e-3, 2e-3});
}

TEST(DelayTraceCsv, LoadedTraceFeedsTraceDelay) {
  auto model = make_trace_delay(load_delay_trace_csv(kDataDir + "/delay_trace_s.csv"));
  RandomStream rng(1);
  EXPECT_DOUBLE_EQ(model->next_delay_s(rng), 0.001);
  EXPECT_DOUBLE_EQ(model->mean_s(), (0.001 + 0.0025 + 0.0004) / 3.0);
}

TEST(DelayTraceCsv, NegativeValueNamesFileAndLine) {
  TempCsv file("# trace\ndelay_ms\n1\n-2\n");
  expect_invalid_argument([&] { load_delay_trace_csv(file.path()); },
                          {file.path() + ":4:", "in [0, 60] s", "'-2'"});
}

TEST(DelayTraceCsv, NaNAndInfinityAreRejected) {
  TempCsv not_a_number("0.001\nnan\n");
  expect_invalid_argument([&] { load_delay_trace_csv(not_a_number.path()); }, {not_a_number.path() + ":2:", "nan"});
  TempCsv infinite("0.001\n0.002\ninf\n");
  expect_invalid_argument([&] { load_delay_trace_csv(infinite.path()); }, {infinite.path() + ":3:", "in [0, 60] s"});
  TempCsv out_of_range("1e999\n");
  expect_invalid_argument([&] { load_delay_trace_csv(out_of_range.path()); }, {out_of_range.path() + ":1:"});
}

TEST(DelayTraceCsv, NonNumericDataLineIsMalformed) {
  TempCsv file("delay_s\n0.001\n0.002x\n");
  expect_invalid_argument([&] { load_delay_trace_csv(file.path()); },
                          {file.path() + ":3:", "last column must be a delay number", "'0.002x'"});
  TempCsv empty_column("0.001\n5,\n");
  expect_invalid_argument([&] { load_delay_trace_csv(empty_column.path()); }, {empty_column.path() + ":2:"});
}

TEST(DelayTraceCsv, EmptyOrHeaderOnlyFileIsAnError) {
  TempCsv empty("");
  expect_invalid_argument([&] { load_delay_trace_csv(empty.path()); }, {empty.path() + ":1:", "no delay samples"});
  TempCsv only_comments("# nothing here\n\n");
  expect_invalid_argument([&] { load_delay_trace_csv(only_comments.path()); },
                          {only_comments.path() + ":3:", "no delay samples"});
  TempCsv header_only("cycle,delay_ms\n");
  expect_invalid_argument([&] { load_delay_trace_csv(header_only.path()); }, {"no delay samples"});
}

TEST(DelayTraceCsv, DevicesAndOversizeSamplesAreRefusedBeforeReading) {
  // /dev/zero never ends a line: refused as not a regular file, without reading it.
  expect_invalid_argument([] { load_delay_trace_csv("/dev/zero"); }, {"/dev/zero", "not a regular file"});
  const TempCsv late("delay_s\n0.001\n61\n");
  expect_invalid_argument([&] { load_delay_trace_csv(late.path()); }, {late.path() + ":3:", "in [0, 60] s"});
}

TEST(DelayTraceCsv, MissingFileIsNamed) {
  const std::string path = kDataDir + "/delay_trace_does_not_exist.csv";
  expect_invalid_argument([&] { load_delay_trace_csv(path); }, {path, "cannot open"});
}

// `ping -D` output as iputils prints it: a header, replies with time stamps, an unreachable
// probe, the statistics.
const char* const kPingOutput =
    "PING 127.0.0.1 (127.0.0.1) 56(84) bytes of data.\n"
    "[1732780000.100000] 64 bytes from 127.0.0.1: icmp_seq=1 ttl=64 time=12.4 ms\n"
    "[1732780001.100000] 64 bytes from 127.0.0.1: icmp_seq=2 ttl=64 time=30.0 ms\n"
    "[1732780002.100000] From 127.0.0.1 icmp_seq=3 Destination Host Unreachable\n"
    "[1732780003.100000] 64 bytes from 127.0.0.1: icmp_seq=4 ttl=64 time=8 ms\n"
    "\n"
    "--- 127.0.0.1 ping statistics ---\n"
    "4 packets transmitted, 3 received, 25% packet loss, time 3004ms\n"
    "rtt min/avg/max/mdev = 8.000/16.800/30.000/9.400 ms\n";

TEST(DelayTracePing, EachReplyGivesHalfItsRoundTripInOrder) {
  TempCsv file(kPingOutput);
  expect_delays(load_delay_trace(file.path()), {6.2e-3, 15e-3, 4e-3});
  expect_delays(load_delay_trace(file.path(), 1.0), {12.4e-3, 30e-3, 8e-3});
}

TEST(DelayTracePing, ACsvFileIsReadAsBefore) {
  expect_delays(load_delay_trace(kDataDir + "/delay_trace_ms.csv"), load_delay_trace_csv(kDataDir + "/delay_trace_ms.csv"));
}

TEST(DelayTracePing, MalformedRepliesAndEmptyOutputNameFileAndLine) {
  TempCsv garbled("PING 127.0.0.1 (127.0.0.1) 56(84) bytes of data.\n64 bytes from 127.0.0.1: icmp_seq=1 time=abc ms\n");
  expect_invalid_argument([&] { load_delay_trace(garbled.path()); },
                          {"ping output", garbled.path() + ":2:", "time=NUMBER ms"});
  TempCsv seconds("64 bytes from 127.0.0.1: icmp_seq=1 ttl=64 time=0.4 s\n");
  expect_invalid_argument([&] { load_delay_trace(seconds.path()); }, {seconds.path() + ":1:"});
  TempCsv huge("64 bytes from 127.0.0.1: icmp_seq=1 ttl=64 time=1e9 ms\n");
  expect_invalid_argument([&] { load_delay_trace(huge.path()); }, {huge.path() + ":1:", "in [0, 60] s"});
  TempCsv no_reply("PING 127.0.0.1 (127.0.0.1) 56(84) bytes of data.\n--- 127.0.0.1 ping statistics ---\n");
  expect_invalid_argument([&] { load_delay_trace(no_reply.path()); }, {no_reply.path() + ":3:", "no replies"});
}

TEST(DelayTracePing, TheRoundTripShareMustBeAFraction) {
  TempCsv file(kPingOutput);
  for (const double share : {0.0, -0.5, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    expect_invalid_argument([&] { load_delay_trace(file.path(), share); }, {"share must be in (0, 1]"});
  }
}

}  // namespace
}  // namespace netmc::netsim
