// The round-trip summary a Modbus master hands the node once per iteration.
#include <gtest/gtest.h>

#include "server/drive/modbus/exchange_statistics.hpp"

namespace netmc::drive::modbus {
namespace {

TEST(ExchangeStatistics, SumsUpPercentilesMaximumAndCountThenStartsAfresh) {
  ExchangeStatistics statistics;
  EXPECT_EQ(statistics.take_summary(), "");
  for (int i = 100; i >= 1; --i) statistics.record(i * 1e-6);
  statistics.record_failure();
  statistics.record_reconnect();
  EXPECT_EQ(statistics.take_summary(),
            "modbus round trip p50 51 us, p99 99 us, max 100 us, 100 requests, 1 failed, 1 reconnect");
  EXPECT_EQ(statistics.take_summary(), "");
  statistics.record(0.0012);
  EXPECT_EQ(statistics.take_summary(), "modbus round trip p50 1.2 ms, p99 1.2 ms, max 1.2 ms, 1 request");
  statistics.record_failure();
  EXPECT_EQ(statistics.take_summary(), "modbus: no answered request, 1 failed");
}

TEST(ExchangeStatistics, PastItsCapacityKeepsAFairSampleAndExactCountAndMaximum) {
  ExchangeStatistics statistics(1000);
  // 100000 round trips, uniform over 1..1000 us, one of 50 ms: the median stays near 500 us.
  for (int i = 0; i < 100000; ++i) statistics.record(((i * 7919) % 1000 + 1) * 1e-6);
  statistics.record(0.05);
  const std::string summary = statistics.take_summary();
  EXPECT_NE(summary.find("max 50 ms, 100001 requests"), std::string::npos) << summary;
  const auto p50 = std::stod(summary.substr(summary.find("p50 ") + 4));
  EXPECT_GT(p50, 400.0) << summary;
  EXPECT_LT(p50, 600.0) << summary;
}

}  // namespace
}  // namespace netmc::drive::modbus
