#pragma once
// Offset and round trip of a remote clock by two-way time transfer (the delay
// request-response exchange of IEEE 1588): t1 probe leaves here, t2 it reaches the remote clock,
// t3 the reply leaves there, t4 it is back here. With a symmetric path,
//   offset = ((t2 - t1) + (t3 - t4)) / 2      (remote minus local)
//   round trip = (t4 - t1) - (t3 - t2)
// and an asymmetric path errs the offset by at most half the round trip, which is therefore
// the stated uncertainty. Of the exchanges in a sliding window, the one with the shortest round
// trip is used: queueing only ever lengthens a trip, so the fastest is the least asymmetric.

#include <cstddef>
#include <deque>
#include <optional>

namespace netmc::netsim {

struct TimeTransferExchange {
  double t1_s = 0.0;  // local clock
  double t2_s = 0.0;  // remote clock
  double t3_s = 0.0;  // remote clock
  double t4_s = 0.0;  // local clock
};

struct ClockOffsetEstimate {
  double offset_s = 0.0;       // remote clock minus local clock
  double round_trip_s = 0.0;   // of the exchange used
  double uncertainty_s = 0.0;  // |error| bound: half that round trip
  double measured_at_s = 0.0;  // local time of that exchange's t4
  std::size_t exchanges = 0;   // exchanges in the window
};

class ClockOffsetEstimator {
 public:
  // Keeps the newest `window` exchanges (at least one).
  explicit ClockOffsetEstimator(std::size_t window = 16);

  // False (and ignored) if the exchange is not causal: t4 < t1, t3 < t2, a round trip shorter
  // than zero, or a non-finite time.
  bool add(const TimeTransferExchange& exchange);
  std::optional<ClockOffsetEstimate> estimate() const;
  void reset() { exchanges_.clear(); }

 private:
  std::size_t window_;
  std::deque<TimeTransferExchange> exchanges_;
};

}  // namespace netmc::netsim
