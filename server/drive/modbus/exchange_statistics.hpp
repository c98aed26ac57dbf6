#pragma once
// Round trips of a fieldbus master's requests, summed up once per iteration for the node's log:
// "modbus round trip p50 180 us, p99 420 us, max 1.2 ms, 3210 requests". Memory is fixed at
// construction: up to `capacity` round trips are kept exactly; past that, a uniform sample of
// them (reservoir sampling), so the percentiles stay fair over a long iteration while the count
// and the maximum stay exact. Recording never allocates.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace netmc::drive::modbus {

class ExchangeStatistics {
 public:
  explicit ExchangeStatistics(std::size_t capacity = 65536);

  void record(double round_trip_s);
  void record_failure();    // a request that got no usable answer
  void record_reconnect();  // the connection was made again

  // The summary since the last call, then everything reset; empty when nothing happened.
  std::string take_summary(const std::string& label = "modbus");

 private:
  std::vector<float> samples_;  // reserved once; seconds
  std::size_t capacity_;
  std::uint64_t count_ = 0;
  std::uint64_t failures_ = 0;
  std::uint64_t reconnects_ = 0;
  double max_s_ = 0.0;
  std::uint64_t random_state_ = 0x9E3779B97F4A7C15ull;
};

}  // namespace netmc::drive::modbus
