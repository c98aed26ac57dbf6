#pragma once
// Virtual-time channel over one LinkModel that handles delays of one period or more: several
// or no messages may arrive within a period, and arrivals may reorder. Messages wait "in
// flight" until the receiver asks for everything that has arrived by a given time.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "netsim/link_model.hpp"
#include "netsim/random_stream.hpp"
#include "netsim/text_format.hpp"

namespace netmc::netsim {

template <typename Payload>
class DelayedChannel {
 public:
  struct Delivery {
    double send_time_s;
    double arrival_time_s;
    std::uint64_t sequence;
    Payload payload;
  };

  struct Counters {
    std::uint64_t sent = 0, lost = 0, delivered = 0;
  };

  explicit DelayedChannel(LinkModel link) : link_(std::move(link)) {}

  // Returns false if the link lost the message. Throws std::invalid_argument for a non-finite time.
  bool send(double send_time_s, std::uint64_t sequence, Payload payload) {
    if (!std::isfinite(send_time_s)) {
      throw std::invalid_argument("delayed channel: send_time_s must be a finite time in s (got " +
                                  format_number(send_time_s) + ")");
    }
    ++counters_.sent;
    const LinkModel::Transit transit = link_.transmit();
    if (transit.lost) {
      ++counters_.lost;
      return false;
    }
    Delivery delivery{send_time_s, send_time_s + transit.delay_s, sequence, std::move(payload)};
    // Kept sorted by (arrival, sequence); equal keys stay in send order.
    const auto position = std::upper_bound(in_flight_.begin(), in_flight_.end(), delivery, arrives_before);
    in_flight_.insert(position, std::move(delivery));
    return true;
  }

  // All arrivals with arrival_time <= time_s, sorted by (arrival_time, sequence), removed from
  // flight. time_s = +inf drains the channel; NaN throws std::invalid_argument.
  std::vector<Delivery> receive_until(double time_s) {
    std::vector<Delivery> arrived;
    receive_until(time_s, arrived);
    return arrived;
  }
  // The same into `arrived` (cleared first): a loop that keeps one buffer allocates nothing.
  void receive_until(double time_s, std::vector<Delivery>& arrived) {
    if (std::isnan(time_s)) {
      throw std::invalid_argument("delayed channel: time_s must be a time in s (got nan)");
    }
    const auto first_pending = std::find_if(in_flight_.begin(), in_flight_.end(),
                                            [time_s](const Delivery& d) { return d.arrival_time_s > time_s; });
    arrived.assign(std::make_move_iterator(in_flight_.begin()), std::make_move_iterator(first_pending));
    in_flight_.erase(in_flight_.begin(), first_pending);
    counters_.delivered += arrived.size();
  }

  std::optional<double> next_arrival_s() const {
    if (in_flight_.empty()) return std::nullopt;
    return in_flight_.front().arrival_time_s;
  }

  std::size_t in_flight() const { return in_flight_.size(); }

  // Arrival time of the message with `sequence` still in flight (a wall-clock loop uses it to
  // know when to act).
  std::optional<double> arrival_of(std::uint64_t sequence) const {
    for (const Delivery& delivery : in_flight_) {
      if (delivery.sequence == sequence) return delivery.arrival_time_s;
    }
    return std::nullopt;
  }

  // Drops everything in flight, zeroes the counters and resets the link with a new stream.
  void reset(RandomStream rng) {
    in_flight_.clear();
    counters_ = Counters{};
    link_.reset(rng);
  }

  const Counters& counters() const { return counters_; }
  const LinkModel& link() const { return link_; }

 private:
  static bool arrives_before(const Delivery& a, const Delivery& b) {
    if (a.arrival_time_s != b.arrival_time_s) return a.arrival_time_s < b.arrival_time_s;
    return a.sequence < b.sequence;
  }

  LinkModel link_;
  std::deque<Delivery> in_flight_;  // sorted by (arrival_time_s, sequence)
  Counters counters_;
};

}  // namespace netmc::netsim
