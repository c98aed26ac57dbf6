#include "server/sim/axis_endpoint.hpp"

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
  downlink_.reset(job_stream(seed_, StreamKind::downlink, index_, iteration));
  lost_ = 0;
}

AxisSample AxisEndpoint::sample() {
  AxisSample s;
  s.true_position_m = axis_.reading().position_m;
  s.measured_m = sensor_.measure(s.true_position_m);
  return s;
}

bool AxisEndpoint::submit_setpoint(double send_time_s, std::uint64_t sequence, double command) {
  const bool delivered = downlink_.send(send_time_s, sequence, command);
  if (!delivered) ++lost_;
  return delivered;
}

const std::vector<AppliedSetpoint>& AxisEndpoint::record(
    const std::vector<netsim::DelayedChannel<double>::Delivery>& deliveries) {
  applied_.clear();
  for (const auto& d : deliveries) applied_.push_back({d.sequence, d.send_time_s, d.arrival_time_s});
  return applied_;
}

const std::vector<AppliedSetpoint>& AxisEndpoint::advance_to(double end_time_s) {
  downlink_.receive_until(end_time_s, deliveries_);
  axis_.advance_to(end_time_s, deliveries_);
  return record(deliveries_);
}

const std::vector<AppliedSetpoint>& AxisEndpoint::apply_arrived(double now_s) {
  downlink_.receive_until(now_s, deliveries_);
  axis_.apply(deliveries_, now_s);
  return record(deliveries_);
}

}  // namespace netmc::sim
