#include "netsim/clock_offset_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace netmc::netsim {

ClockOffsetEstimator::ClockOffsetEstimator(std::size_t window) : window_(std::max<std::size_t>(window, 1)) {}

bool ClockOffsetEstimator::add(const TimeTransferExchange& e) {
  const bool finite = std::isfinite(e.t1_s) && std::isfinite(e.t2_s) && std::isfinite(e.t3_s) &&
                      std::isfinite(e.t4_s);
  if (!finite || e.t4_s < e.t1_s || e.t3_s < e.t2_s || (e.t4_s - e.t1_s) < (e.t3_s - e.t2_s)) {
    return false;
  }
  exchanges_.push_back(e);
  while (exchanges_.size() > window_) exchanges_.pop_front();
  return true;
}

std::optional<ClockOffsetEstimate> ClockOffsetEstimator::estimate() const {
  if (exchanges_.empty()) return std::nullopt;
  const auto round_trip = [](const TimeTransferExchange& e) { return (e.t4_s - e.t1_s) - (e.t3_s - e.t2_s); };
  const auto best = std::min_element(exchanges_.begin(), exchanges_.end(),
                                     [&](const auto& a, const auto& b) { return round_trip(a) < round_trip(b); });
  ClockOffsetEstimate out;
  out.offset_s = ((best->t2_s - best->t1_s) + (best->t3_s - best->t4_s)) / 2.0;
  out.round_trip_s = round_trip(*best);
  out.uncertainty_s = out.round_trip_s / 2.0;
  out.measured_at_s = best->t4_s;
  out.exchanges = exchanges_.size();
  return out;
}

}  // namespace netmc::netsim
