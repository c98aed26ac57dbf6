#include "netsim/freshness_filter.hpp"

namespace netmc::netsim {

bool FreshnessFilter::accept(std::uint64_t sequence) {
  if (last_accepted_ && sequence <= *last_accepted_) {
    ++stale_dropped_;
    return false;
  }
  last_accepted_ = sequence;
  return true;
}

void FreshnessFilter::reset() {
  last_accepted_.reset();
  stale_dropped_ = 0;
}

std::uint64_t FreshnessFilter::stale_dropped() const { return stale_dropped_; }

std::optional<std::uint64_t> FreshnessFilter::last_accepted() const { return last_accepted_; }

}  // namespace netmc::netsim
