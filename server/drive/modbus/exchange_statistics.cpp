#include "server/drive/modbus/exchange_statistics.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "server/drive/modbus/duration_text.hpp"

namespace netmc::drive::modbus {

ExchangeStatistics::ExchangeStatistics(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)) {
  samples_.reserve(capacity_);
}

void ExchangeStatistics::record(double round_trip_s) {
  ++count_;
  max_s_ = std::max(max_s_, round_trip_s);
  if (samples_.size() < capacity_) {
    samples_.push_back(static_cast<float>(round_trip_s));
    return;
  }
  // Reservoir sampling: the n-th round trip replaces a kept one with probability capacity / n.
  random_state_ ^= random_state_ << 13;
  random_state_ ^= random_state_ >> 7;
  random_state_ ^= random_state_ << 17;
  const std::uint64_t slot = random_state_ % count_;
  if (slot < capacity_) samples_[slot] = static_cast<float>(round_trip_s);
}

void ExchangeStatistics::record_failure() { ++failures_; }

void ExchangeStatistics::record_reconnect() { ++reconnects_; }

std::string ExchangeStatistics::take_summary(const std::string& label) {
  if (count_ == 0 && failures_ == 0 && reconnects_ == 0) return {};
  std::string out;
  if (!samples_.empty()) {
    const auto percentile = [&](double p) {
      const auto rank = static_cast<std::size_t>(p * static_cast<double>(samples_.size() - 1) + 0.5);
      std::nth_element(samples_.begin(), samples_.begin() + static_cast<std::ptrdiff_t>(rank), samples_.end());
      return static_cast<double>(samples_[rank]);
    };
    const double p50 = percentile(0.50), p99 = percentile(0.99);
    out = fmt::format("{} round trip p50 {}, p99 {}, max {}, {} request{}", label, format_duration(p50),
                      format_duration(p99), format_duration(max_s_), count_, count_ == 1 ? "" : "s");
  } else {
    out = fmt::format("{}: no answered request", label);
  }
  if (failures_ > 0) out += fmt::format(", {} failed", failures_);
  if (reconnects_ > 0) out += fmt::format(", {} reconnect{}", reconnects_, reconnects_ == 1 ? "" : "s");
  samples_.clear();  // keeps its capacity
  count_ = failures_ = reconnects_ = 0;
  max_s_ = 0.0;
  return out;
}

}  // namespace netmc::drive::modbus
