#include "server/console/live_feed.hpp"

namespace netmc::console {

void LiveFeed::on_cycle(const sim::LiveCycle& cycle) noexcept {
  // The control loop never waits for the console: a busy feed loses this cycle.
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) {
    missed_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (count_ == kCapacity) ++dropped_;  // the oldest is overwritten
  else ++count_;
  ring_[head_] = cycle;
  head_ = (head_ + 1) % kCapacity;
}

LiveFeed::Taken LiveFeed::take() {
  Taken taken;
  std::lock_guard lock(mutex_);
  taken.cycles.reserve(count_);
  const std::size_t first = (head_ + kCapacity - count_) % kCapacity;
  for (std::size_t i = 0; i < count_; ++i) taken.cycles.push_back(ring_[(first + i) % kCapacity]);
  count_ = 0;
  taken.dropped = dropped_ + missed_.exchange(0, std::memory_order_relaxed);
  dropped_ = 0;
  return taken;
}

std::vector<sim::LiveCycle> decimate(const std::vector<sim::LiveCycle>& cycles, std::size_t limit) {
  if (limit == 0 || cycles.size() <= limit) return cycles;
  const std::size_t step = (cycles.size() + limit - 1) / limit;
  std::vector<sim::LiveCycle> kept;
  kept.reserve(limit);
  // Counted back from the newest, so the latest cycle is always shown.
  const std::size_t last = cycles.size() - 1;
  for (std::size_t back = 0; back <= last && kept.size() < limit; back += step) kept.push_back(cycles[last - back]);
  return {kept.rbegin(), kept.rend()};
}

}  // namespace netmc::console
