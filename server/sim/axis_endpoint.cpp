#include "server/sim/axis_endpoint.hpp"

#include <algorithm>
#include <cmath>

#include "server/drive/simulated_drive.hpp"
#include "server/sim/random_streams.hpp"

namespace netmc::sim {

AxisEndpoint::AxisEndpoint(std::shared_ptr<drive::Drive> drive, const ContourJob& job, std::size_t axis,
                           drive::AxisLimits limits)
    : axis_(std::move(drive), job.command_limit, limits),
      // The sensor's noise stream runs on across iterations: ILC cannot learn the noise.
      sensor_(job.sensor, job.seed, stream_id(StreamKind::sensor, axis, 0)),
      downlink_(netsim::LinkModel(job.downlink.delay->clone(), job.downlink.loss->clone(),
                                  job_stream(job.seed, StreamKind::downlink, axis, 0))),
      seed_(job.seed),
      index_(axis),
      sample_period_s_(job.sample_period_s) {}

std::shared_ptr<drive::Drive> AxisEndpoint::simulated_drive(const ContourJob& job, std::size_t axis) {
  auto simulated = std::make_shared<drive::SimulatedDrive>(job.axes.at(axis)->clone(), "sim:" + job.plant_name);
  simulated->open();
  return simulated;
}

void AxisEndpoint::follow_job_reference(const ContourJob& job) {
  axis_.follow_reference(
      [contour = job.contour(), index = index_, point = control::GroupReference{}](double time_s) mutable {
        contour->sample(time_s, point);
        return point.position(static_cast<Eigen::Index>(index));
      },
      job.sample_period_s);
}

void AxisEndpoint::begin_iteration(std::size_t iteration, double start_position_m) {
  axis_.begin_iteration(start_position_m);
  planned_.clear();
  held_.clear();
  packets_in_flight_.clear();
  packets_waiting_.clear();
  playing_.reset();
  next_index_ = 0;
  plays_ = 0;
  stale_packets_ = horizon_cycles_ = held_cycles_ = 0;
  last_instant_ = Instant::own;
  last_instant_s_ = -std::numeric_limits<double>::infinity();
  downlink_.reset(job_stream(seed_, StreamKind::downlink, index_, iteration));
  lost_ = 0;
}

AxisSample AxisEndpoint::sample() {
  AxisSample s;
  s.true_position_m = axis_.reading().position_m;
  s.measured_m = sensor_.measure(s.true_position_m);
  return s;
}

bool AxisEndpoint::submit_setpoint(double send_time_s, std::uint64_t sequence, double command, double acts_at_s) {
  const bool delivered = downlink_.send(send_time_s, sequence, command);
  if (!delivered) {
    ++lost_;
  } else if (std::isfinite(acts_at_s)) {
    // Bounded like the channel's flight: a plan is dropped with its setpoint's arrival.
    if (planned_.size() >= kMaxPlanned) planned_.erase(planned_.begin());
    planned_.push_back({sequence, acts_at_s});
  }
  return delivered;
}

bool AxisEndpoint::submit_packet(double send_time_s, std::uint64_t sequence, double acts_at_s,
                                 std::vector<double> commands) {
  if (commands.empty()) return false;  // nothing to play: the caller sends at least the setpoint's own
  if (!downlink_.send(send_time_s, sequence, commands.front())) {
    ++lost_;
    return false;
  }
  if (packets_in_flight_.size() >= kMaxPlanned) packets_in_flight_.erase(packets_in_flight_.begin());
  packets_in_flight_.push_back({sequence, send_time_s, acts_at_s, 0.0, std::move(commands)});
  return true;
}

std::pair<double, double> AxisEndpoint::first_instant(const Packet& packet) const {
  if (!(packet.network_arrival_s > packet.acts_at_s)) return {packet.acts_at_s, 0.0};
  // The tolerance keeps an arrival a rounding error after an instant on that instant.
  const double index = std::ceil((packet.network_arrival_s - packet.acts_at_s) / sample_period_s_ - 1e-9);
  return {packet.acts_at_s + index * sample_period_s_, index};
}

std::optional<double> AxisEndpoint::next_arrival_s() const {
  auto next = downlink_.next_arrival_s();
  const auto earlier = [&](double at) {
    if (!next || at < *next) next = at;
  };
  if (!held_.empty()) earlier(held_.front().delivery.arrival_time_s);
  for (const auto& packet : packets_waiting_) earlier(first_instant(packet).first);
  if (playing_ && next_index_ < playing_->commands.size()) {
    earlier(playing_->acts_at_s + static_cast<double>(next_index_) * sample_period_s_);
  }
  return next;
}

void AxisEndpoint::play_packets(std::vector<Delivery>& deliveries, double until_s) {
  origins_.clear();
  for (const auto& delivery : deliveries) {
    const auto it = std::find_if(packets_in_flight_.begin(), packets_in_flight_.end(),
                                 [&](const Packet& p) { return p.sequence == delivery.sequence; });
    if (it == packets_in_flight_.end()) continue;
    Packet packet = std::move(*it);
    packets_in_flight_.erase(it);
    packet.network_arrival_s = delivery.arrival_time_s;
    // Held at most kMaxHoldS, as a planned setpoint: a faulty plan cannot park the axis.
    if (!std::isfinite(packet.acts_at_s)) packet.acts_at_s = packet.network_arrival_s;
    packet.acts_at_s = std::min(packet.acts_at_s, packet.network_arrival_s + kMaxHoldS);
    if (!axis_.accept_horizon(packet.sequence, packet.commands)) continue;
    if (packets_waiting_.size() >= kMaxPlanned) packets_waiting_.erase(packets_waiting_.begin());
    packets_waiting_.push_back(std::move(packet));
  }
  deliveries.clear();
  const double h = sample_period_s_;
  const double same_instant = h / 4.0;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  while (true) {
    // Not fresher than the one playing: never plays.
    std::erase_if(packets_waiting_, [&](const Packet& p) {
      const bool stale = playing_ && p.sequence <= playing_->sequence;
      if (stale) ++stale_packets_;
      return stale;
    });
    double start = kNever;
    for (const auto& p : packets_waiting_) start = std::min(start, first_instant(p).first);
    const double next = playing_ ? playing_->acts_at_s + static_cast<double>(next_index_) * h : kNever;
    const double at = std::min(start, next);
    if (!(at <= until_s)) break;
    bool beyond_horizon = false;
    // The freshest setpoint that begins at this instant takes over.
    auto fresh = packets_waiting_.end();
    for (auto it = packets_waiting_.begin(); it != packets_waiting_.end(); ++it) {
      if (first_instant(*it).first <= at + same_instant && (fresh == packets_waiting_.end() || it->sequence > fresh->sequence)) {
        fresh = it;
      }
    }
    if (fresh != packets_waiting_.end()) {
      // A setpoint that arrived at the very instant an older one's horizon (or the hold) took:
      // that instant is its, not covered.
      if (std::abs(at - last_instant_s_) <= same_instant) {
        if (last_instant_ == Instant::horizon) --horizon_cycles_;
        if (last_instant_ == Instant::held) --held_cycles_;
      }
      const double index = first_instant(*fresh).second;
      playing_ = std::move(*fresh);
      packets_waiting_.erase(fresh);
      // One that came after its horizon's end still is the freshest the axis has: its last command
      // acts at once and holds, as a late setpoint without packets acts on arrival. (Dropped, it
      // would never be reported, and a server that plans by the reported delays would never
      // learn one longer than its horizon.)
      beyond_horizon = index >= static_cast<double>(playing_->commands.size());
      next_index_ = beyond_horizon ? playing_->commands.size() - 1 : static_cast<std::size_t>(index);
      // Its instants go on from this one: the last command sits at this instant of its grid.
      if (beyond_horizon) playing_->acts_at_s += (index - static_cast<double>(next_index_)) * h;
    } else if (next_index_ >= playing_->commands.size()) {
      // Nothing left to play: the last command holds, at every instant until a fresh one begins.
      const double last = std::min(until_s, start - same_instant);
      const double instants = std::max(1.0, std::floor((last - next) / h + 1e-9) + 1.0);
      held_cycles_ += static_cast<std::uint64_t>(instants);
      next_index_ += static_cast<std::size_t>(instants);
      last_instant_ = Instant::held;
      last_instant_s_ = next + (instants - 1.0) * h;
      continue;
    }
    const double command = playing_->commands[next_index_];
    if (!axis_.accept_horizon_entry(playing_->sequence, next_index_, playing_->commands.size(), command)) break;
    deliveries.push_back({playing_->send_time_s, at, ++plays_, command});
    origins_.push_back({playing_->sequence, playing_->network_arrival_s, static_cast<std::uint32_t>(next_index_)});
    if (beyond_horizon) {
      ++held_cycles_;
      last_instant_ = Instant::held;
    } else {
      if (next_index_ > 0) ++horizon_cycles_;
      last_instant_ = next_index_ > 0 ? Instant::horizon : Instant::own;
    }
    last_instant_s_ = at;
    ++next_index_;
  }
}

void AxisEndpoint::play_out(std::vector<Delivery>& deliveries, double until_s) {
  origins_.clear();
  if (planned_.empty() && held_.empty()) {
    for (const auto& d : deliveries) origins_.push_back({d.sequence, d.arrival_time_s, 0});
    return;
  }
  for (auto& delivery : deliveries) {
    const auto plan = std::find_if(planned_.begin(), planned_.end(),
                                   [&](const Planned& p) { return p.sequence == delivery.sequence; });
    double acts_at = delivery.arrival_time_s;
    if (plan != planned_.end()) {
      // Held at most kMaxHoldS: a plan from a faulty server cannot park the axis's commands.
      acts_at = std::clamp(plan->acts_at_s, acts_at, acts_at + kMaxHoldS);
      planned_.erase(plan);
    }
    const double arrived = delivery.arrival_time_s;
    delivery.arrival_time_s = acts_at;
    held_.push_back({delivery, arrived});
  }
  deliveries.clear();
  // Due now, in the channel's order (time, then sequence); the rest wait.
  std::stable_sort(held_.begin(), held_.end(), [](const Held& a, const Held& b) {
    return a.delivery.arrival_time_s < b.delivery.arrival_time_s ||
           (a.delivery.arrival_time_s == b.delivery.arrival_time_s && a.delivery.sequence < b.delivery.sequence);
  });
  std::size_t due = 0;
  while (due < held_.size() && held_[due].delivery.arrival_time_s <= until_s) {
    deliveries.push_back(held_[due].delivery);
    origins_.push_back({held_[due].delivery.sequence, held_[due].network_arrival_s, 0});
    ++due;
  }
  held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(due));
}

const std::vector<AppliedSetpoint>& AxisEndpoint::record(const std::vector<Delivery>& deliveries) {
  applied_.clear();
  for (std::size_t i = 0; i < deliveries.size(); ++i) {
    const auto& d = deliveries[i];
    const Origin& o = origins_[i];
    applied_.push_back({o.sequence, d.send_time_s, d.arrival_time_s, o.network_arrival_s, o.horizon_index});
  }
  return applied_;
}

void AxisEndpoint::receive(double until_s) {
  downlink_.receive_until(until_s, deliveries_);
  if (!packets_in_flight_.empty() || !packets_waiting_.empty() || playing_) {
    play_packets(deliveries_, until_s);
  } else {
    play_out(deliveries_, until_s);
  }
}

const std::vector<AppliedSetpoint>& AxisEndpoint::advance_to(double end_time_s) {
  // An instant at the end itself is played now (the predictor counts on reports complete up to
  // the sample): a setpoint that arrives at that very instant takes it over in the next call.
  receive(end_time_s);
  axis_.advance_to(end_time_s, deliveries_);
  return record(deliveries_);
}

const std::vector<AppliedSetpoint>& AxisEndpoint::apply_arrived(double now_s) {
  receive(now_s);
  axis_.apply(deliveries_, now_s);
  return record(deliveries_);
}

}  // namespace netmc::sim
