#include "server/axis/axis_node_link.hpp"

#include "dds_typesPubSubTypes.h"
#include "idl/job.pb.h"
#include "server/dds/topics.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::axis {

AxisNodeLink::AxisNodeLink(dds::DdsContext& context, AxisNodeConfig config)
    : config_(std::move(config)),
      feedback_writer_(context.writer(
          context.topic<netmc::dds::FeedbackPubSubType>(dds::kFeedbackTopic), dds::Delivery::control)),
      status_writer_(context.writer(
          context.topic<netmc::dds::NodeStatusPubSubType>(dds::kNodeStatusTopic),
          dds::Delivery::status)),
      setpoints_(context.reader(context.topic<netmc::dds::SetpointPubSubType>(dds::kSetpointTopic),
                                dds::Delivery::control)) {}

void AxisNodeLink::publish_status(netmc::dds::NodeHealth health, const std::string& detail) {
  netmc::dds::NodeStatus status;
  status.node(config_.node);
  status.axis_ids(config_.axis_ids);
  status.plant(config_.plant);
  status.clock(config_.clock);
  status.health(health);
  status.detail(detail);
  status_writer_->write(&status);
}

JobAxis AxisNodeLink::start_job(const netmc::dds::Setpoint& begin) {
  // A new server may not have matched our feedback yet; samples sent before that are lost.
  if (!dds::wait_for_readers(feedback_writer_, 1, std::chrono::seconds(5))) {
    throw std::runtime_error("no server reads this node's feedback");
  }
  netmc::v1::JobSpec spec;
  if (!spec.ParseFromArray(begin.job_spec().data(), static_cast<int>(begin.job_spec().size()))) {
    throw std::invalid_argument("malformed job spec");
  }
  const sim::ContourJob job = job::build_contour_job(spec);
  JobAxis axis;
  axis.endpoint = std::make_unique<sim::AxisEndpoint>(job.axes.at(begin.axis_id())->clone(), job,
                                                      begin.axis_id());
  axis.job_id = begin.job_id();
  axis.cycles = job.cycles();
  axis.sample_period_s = job.sample_period_s;
  return axis;
}

void append_applied(netmc::dds::Feedback& feedback, const std::vector<sim::AppliedSetpoint>& applied) {
  for (const auto& a : applied) {
    netmc::dds::AppliedSetpoint entry;
    entry.cycle(a.sequence);
    entry.send_time_s(a.send_time_s);
    entry.arrival_time_s(a.arrival_time_s);
    feedback.applied().push_back(entry);
  }
}

void set_sample(netmc::dds::Feedback& feedback, std::uint64_t cycle, double time_s,
                const sim::AxisSample& sample) {
  feedback.cycle(cycle);
  feedback.kind(netmc::dds::FEEDBACK_SAMPLE);
  feedback.position_m(sample.measured_m);
  feedback.true_position_m(sample.true_position_m);
  feedback.sample_time_s(time_s);
}

}  // namespace netmc::axis
