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
      index_(axis) {}

std::shared_ptr<drive::Drive> AxisEndpoint::simulated_drive(const ContourJob& job, std::size_t axis) {
  auto simulated = std::make_shared<drive::SimulatedDrive>(job.axes.at(axis)->clone(), "sim:" + job.plant_name);
  simulated->open();
  return simulated;
}

void AxisEndpoint::begin_iteration(std::size_t iteration, double start_position_m) {
  axis_.begin_iteration(start_position_m);
  planned_.clear();
  held_.clear();
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

void AxisEndpoint::play_out(std::vector<Delivery>& deliveries, double until_s) {
  network_arrivals_.clear();
  if (planned_.empty() && held_.empty()) {
    for (const auto& d : deliveries) network_arrivals_.push_back(d.arrival_time_s);
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
    network_arrivals_.push_back(held_[due].network_arrival_s);
    ++due;
  }
  held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(due));
}

const std::vector<AppliedSetpoint>& AxisEndpoint::record(const std::vector<Delivery>& deliveries) {
  applied_.clear();
  for (std::size_t i = 0; i < deliveries.size(); ++i) {
    const auto& d = deliveries[i];
    applied_.push_back({d.sequence, d.send_time_s, d.arrival_time_s, network_arrivals_[i]});
  }
  return applied_;
}

const std::vector<AppliedSetpoint>& AxisEndpoint::advance_to(double end_time_s) {
  downlink_.receive_until(end_time_s, deliveries_);
  play_out(deliveries_, end_time_s);
  axis_.advance_to(end_time_s, deliveries_);
  return record(deliveries_);
}

const std::vector<AppliedSetpoint>& AxisEndpoint::apply_arrived(double now_s) {
  downlink_.receive_until(now_s, deliveries_);
  play_out(deliveries_, now_s);
  axis_.apply(deliveries_, now_s);
  return record(deliveries_);
}

}  // namespace netmc::sim
