#pragma once
// The delays of one iteration (tau, tau_sc, tau_cc, tau_ca) in bounded memory: mean and max
// exact over every sample; p50/p99 exact while an iteration has at most kExactSamples of them
// (every preset), beyond that from a histogram of 0.1 % wide bins (relative error <= 0.05 %),
// so a long iteration costs at most about 16 MiB per statistic instead of 8 bytes a sample.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace netmc::sim {

class DelayStatistics {
 public:
  static constexpr std::size_t kExactSamples = std::size_t{1} << 21;

  void clear();
  // Room for an iteration of `samples` made before it starts, so that adding them allocates
  // nothing (a realtime loop): the exact vector if they fit, else the histogram from the first.
  void reserve_for(std::size_t samples);
  void add(double value_s);
  // The newest sample measured again (a realtime cycle's compute delay once it is known).
  void replace_last(double value_s);
  bool empty() const { return count_ == 0; }
  std::size_t size() const { return count_; }
  double mean() const;
  double max() const;
  double percentile(double fraction) const;
  // True once the samples went beyond kExactSamples (percentiles from the histogram).
  bool binned() const { return !bins_.empty(); }

 private:
  void commit(double value_s);
  void bin(double value_s);
  std::size_t bin_of(double value_s) const;
  double value_of(std::size_t bin) const;

  std::vector<double> exact_;       // every sample while there are few
  std::vector<std::uint64_t> bins_;  // counts once there are many
  std::size_t count_ = 0;
  double sum_ = 0.0;
  double max_ = -std::numeric_limits<double>::infinity();  // of the binned samples
  bool has_pending_ = false;         // the newest sample, not yet committed (replace_last)
  double pending_ = 0.0;
};

}  // namespace netmc::sim
