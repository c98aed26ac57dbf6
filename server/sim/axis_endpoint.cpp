#include "server/sim/axis_endpoint.hpp"

#include "server/sim/random_streams.hpp"

namespace netmc::sim {

AxisEndpoint::AxisEndpoint(std::unique_ptr<plant::AxisPlant> plant, const ContourJob& job,
                           std::size_t axis, AxisLimits limits)
    : axis_(std::move(plant),
            // The sensor's noise stream runs on across iterations: ILC cannot learn the noise.
            plant::PositionSensor(job.sensor, job.seed, stream_id(StreamKind::sensor, axis, 0)),
            job.command_limit, limits),
      downlink_(netsim::LinkModel(job.downlink.delay->clone(), job.downlink.loss->clone(),
                                  job_stream(job.seed, StreamKind::downlink, axis, 0))),
      seed_(job.seed),
      index_(axis) {}

void AxisEndpoint::begin_iteration(std::size_t iteration, double start_position_m) {
  axis_.reset(start_position_m);
  downlink_.reset(job_stream(seed_, StreamKind::downlink, index_, iteration));
  lost_ = 0;
}

AxisSample AxisEndpoint::sample() {
  AxisSample s;
  s.true_position_m = axis_.plant().position();
  s.measured_m = axis_.measure();
  return s;
}

bool AxisEndpoint::submit_setpoint(double send_time_s, std::uint64_t sequence, double command) {
  const bool delivered = downlink_.send(send_time_s, sequence, command);
  if (!delivered) ++lost_;
  return delivered;
}

const std::vector<AppliedSetpoint>& AxisEndpoint::advance_to(double end_time_s) {
  downlink_.receive_until(end_time_s, deliveries_);
  axis_.advance_to(end_time_s, deliveries_);
  applied_.clear();
  for (const auto& d : deliveries_) applied_.push_back({d.sequence, d.send_time_s, d.arrival_time_s});
  return applied_;
}

}  // namespace netmc::sim
