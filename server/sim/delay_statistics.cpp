#include "server/sim/delay_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace netmc::sim {
namespace {

// Bins of |value| from kSmallest to kLargest seconds, kRatio apart, one set per sign, and one bin
// for |value| < kSmallest (taken as 0).
constexpr double kSmallest = 1e-9;
constexpr double kLargest = 1e4;
constexpr double kRatio = 1.001;
const double kLogRatio = std::log(kRatio);
const std::size_t kBinsPerSign = static_cast<std::size_t>(std::ceil(std::log(kLargest / kSmallest) / kLogRatio)) + 1;

}  // namespace

void DelayStatistics::clear() {
  exact_.clear();
  bins_.clear();
  bins_.shrink_to_fit();
  count_ = 0;
  sum_ = 0.0;
  max_ = -std::numeric_limits<double>::infinity();
  has_pending_ = false;
}

void DelayStatistics::reserve_for(std::size_t samples) {
  if (count_ != 0) return;
  if (samples <= kExactSamples) {
    exact_.reserve(samples);
  } else {
    std::vector<double>().swap(exact_);
    bins_.assign(2 * kBinsPerSign + 1, 0);
  }
}

void DelayStatistics::add(double value_s) {
  if (has_pending_) commit(pending_);
  pending_ = value_s;
  has_pending_ = true;
  ++count_;
}

void DelayStatistics::replace_last(double value_s) {
  if (has_pending_) pending_ = value_s;
}

void DelayStatistics::commit(double value_s) {
  if (bins_.empty() && exact_.size() < kExactSamples) {
    exact_.push_back(value_s);
    return;
  }
  if (bins_.empty()) {
    // Too many to keep: from here on, counts per bin.
    bins_.assign(2 * kBinsPerSign + 1, 0);
    for (const double v : exact_) bin(v);
    std::vector<double>().swap(exact_);
  }
  bin(value_s);
}

void DelayStatistics::bin(double value_s) {
  ++bins_[bin_of(value_s)];
  sum_ += value_s;
  max_ = std::max(max_, value_s);
}

// Bins in value order: negative (largest magnitude first), the zero bin, positive.
std::size_t DelayStatistics::bin_of(double value_s) const {
  const double magnitude = std::abs(value_s);
  if (!(magnitude >= kSmallest)) return kBinsPerSign;
  const auto step = std::min(kBinsPerSign - 1, static_cast<std::size_t>(std::log(magnitude / kSmallest) / kLogRatio));
  return value_s > 0.0 ? kBinsPerSign + 1 + step : kBinsPerSign - 1 - step;
}

double DelayStatistics::value_of(std::size_t bin) const {
  if (bin == kBinsPerSign) return 0.0;
  const std::size_t step = bin > kBinsPerSign ? bin - kBinsPerSign - 1 : kBinsPerSign - 1 - bin;
  const double magnitude = kSmallest * std::pow(kRatio, static_cast<double>(step) + 0.5);  // the bin's middle
  return bin > kBinsPerSign ? magnitude : -magnitude;
}

double DelayStatistics::mean() const {
  if (count_ == 0) return 0.0;
  if (!binned()) {
    // As the whole vector was summed before (the presets' results stay bit-identical).
    double sum = 0.0;
    for (const double v : exact_) sum += v;
    if (has_pending_) sum += pending_;
    return sum / static_cast<double>(count_);
  }
  return (sum_ + (has_pending_ ? pending_ : 0.0)) / static_cast<double>(count_);
}

double DelayStatistics::max() const {
  if (count_ == 0) return 0.0;
  double out = binned() ? max_ : (exact_.empty() ? pending_ : *std::max_element(exact_.begin(), exact_.end()));
  if (has_pending_) out = std::max(out, pending_);
  return out;
}

double DelayStatistics::percentile(double fraction) const {
  if (count_ == 0) return 0.0;
  const auto rank = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(count_)));
  const std::size_t index = std::min(count_ - 1, rank == 0 ? 0 : rank - 1);
  if (!binned()) {
    std::vector<double> values = exact_;
    if (has_pending_) values.push_back(pending_);
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index), values.end());
    return values[index];
  }
  // The pending sample is counted where it falls.
  const std::size_t pending_bin = has_pending_ ? bin_of(pending_) : bins_.size();
  std::size_t seen = 0;
  for (std::size_t b = 0; b < bins_.size(); ++b) {
    seen += bins_[b] + (b == pending_bin ? 1 : 0);
    if (seen > index) return value_of(b);
  }
  return max();
}

}  // namespace netmc::sim
