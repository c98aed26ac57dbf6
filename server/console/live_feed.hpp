#pragma once
// The cycles of one running job on their way to the console: the job's control loop hands each
// computed cycle over without waiting (a cycle that finds the feed busy is dropped and counted),
// the feed keeps the newest kCapacity (older ones are dropped and counted), and the console
// takes what has gathered every tenth of a second.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

#include "server/sim/cycle_listener.hpp"

namespace netmc::console {

class LiveFeed final : public sim::CycleListener {
 public:
  static constexpr std::size_t kCapacity = 4096;

  void on_cycle(const sim::LiveCycle& cycle) noexcept override;

  struct Taken {
    std::vector<sim::LiveCycle> cycles;  // oldest first
    std::uint64_t dropped = 0;           // since the last take
  };
  // The cycles gathered since the last call.
  Taken take();

 private:
  std::mutex mutex_;
  std::vector<sim::LiveCycle> ring_ = std::vector<sim::LiveCycle>(kCapacity);
  std::size_t head_ = 0;   // next slot to write
  std::size_t count_ = 0;  // filled slots
  std::uint64_t dropped_ = 0;
  std::atomic<std::uint64_t> missed_{0};  // cycles that found the feed busy
};

// Every k-th of `cycles` (k the smallest that leaves at most `limit`), the last one always kept.
std::vector<sim::LiveCycle> decimate(const std::vector<sim::LiveCycle>& cycles, std::size_t limit);

}  // namespace netmc::console
