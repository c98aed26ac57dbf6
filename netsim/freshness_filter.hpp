#pragma once
// Receiver-side guard against reordering and duplicates: a message is used only if its
// sequence number is newer than every message accepted so far; older ones are stale (a newer
// command or measurement has already been applied) and are counted, then dropped.

#include <cstdint>
#include <optional>

namespace netmc::netsim {

class FreshnessFilter {
 public:
  bool accept(std::uint64_t sequence);  // true if newer than every accepted one; else counts a stale drop
  void reset();                          // forget everything (e.g. between ILC iterations)
  std::uint64_t stale_dropped() const;
  std::optional<std::uint64_t> last_accepted() const;

 private:
  std::optional<std::uint64_t> last_accepted_;
  std::uint64_t stale_dropped_ = 0;
};

}  // namespace netmc::netsim
