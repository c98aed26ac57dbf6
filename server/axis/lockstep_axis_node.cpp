#include "server/axis/lockstep_axis_node.hpp"

#include <iostream>

#include "dds_typesPubSubTypes.h"
#include "idl/job.pb.h"
#include "server/dds/topics.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::axis {
namespace {

using netmc::dds::Feedback;
using netmc::dds::Setpoint;

void fill_counters(Feedback& feedback, const sim::AxisEndpoint& endpoint) {
  feedback.lost_setpoints(endpoint.lost_setpoints());
  feedback.stale_setpoints(endpoint.stale_setpoints());
}

}  // namespace

LockstepAxisNode::LockstepAxisNode(dds::DdsContext& context, AxisNodeConfig config)
    : config_(std::move(config)),
      feedback_writer_(context.writer(
          context.topic<netmc::dds::FeedbackPubSubType>(dds::kFeedbackTopic),
          dds::Delivery::control)),
      status_writer_(context.writer(
          context.topic<netmc::dds::NodeStatusPubSubType>(dds::kNodeStatusTopic),
          dds::Delivery::status)),
      setpoints_(context.reader(context.topic<netmc::dds::SetpointPubSubType>(dds::kSetpointTopic),
                                dds::Delivery::control)) {
  for (const auto id : config_.axis_ids) axes_[id] = OwnedAxis{};
}

void LockstepAxisNode::publish_status(netmc::dds::NodeHealth health, const std::string& detail) {
  netmc::dds::NodeStatus status;
  status.node(config_.node);
  status.axis_ids(config_.axis_ids);
  status.plant(config_.plant);
  status.clock("lockstep");
  status.health(health);
  status.detail(detail);
  status_writer_->write(&status);
}

void LockstepAxisNode::serve(const std::atomic<bool>& stop) {
  publish_status(netmc::dds::NODE_IDLE, "ready");
  auto last_status = std::chrono::steady_clock::now();
  while (!stop.load()) {
    if (auto setpoint = setpoints_.take(std::chrono::milliseconds(200))) {
      try {
        handle(*setpoint);
      } catch (const std::exception& error) {
        // A job this node cannot run must not take the node down: report it and stay ready.
        publish_status(netmc::dds::NODE_FAULT, std::string("job ") +
                                                   std::to_string(setpoint->job_id()) + ": " +
                                                   error.what());
        for (auto& [id, axis] : axes_) axis.endpoint.reset();
      }
    }
    if (std::chrono::steady_clock::now() - last_status > std::chrono::seconds(1)) {
      bool running = false;
      for (const auto& [id, axis] : axes_) running = running || axis.endpoint != nullptr;
      publish_status(running ? netmc::dds::NODE_RUNNING : netmc::dds::NODE_IDLE,
                     running ? "running a job" : "ready");
      last_status = std::chrono::steady_clock::now();
    }
  }
}

void LockstepAxisNode::handle(const Setpoint& setpoint) {
  const auto owned = axes_.find(setpoint.axis_id());
  if (owned == axes_.end()) return;  // another node's axis
  OwnedAxis& axis = owned->second;

  Feedback feedback;
  feedback.axis_id(setpoint.axis_id());
  feedback.job_id(setpoint.job_id());
  feedback.iteration(setpoint.iteration());

  switch (setpoint.kind()) {
    case netmc::dds::SETPOINT_BEGIN_ITERATION: {
      if (!setpoint.job_spec().empty()) {
        // A new server may not have matched our feedback yet; samples sent before that are lost.
        if (!dds::wait_for_readers(feedback_writer_, 1, std::chrono::seconds(5))) {
          throw std::runtime_error("no server reads this node's feedback");
        }
        netmc::v1::JobSpec spec;
        if (!spec.ParseFromArray(setpoint.job_spec().data(),
                                 static_cast<int>(setpoint.job_spec().size()))) {
          publish_status(netmc::dds::NODE_FAULT, "job " + std::to_string(setpoint.job_id()) +
                                                     ": malformed job spec");
          return;
        }
        const sim::ContourJob job = job::build_contour_job(spec);
        axis.endpoint = std::make_unique<sim::AxisEndpoint>(
            job.axes.at(setpoint.axis_id())->clone(), job, setpoint.axis_id());
        axis.job_id = setpoint.job_id();
        axis.cycles = job.cycles();
        axis.sample_period_s = job.sample_period_s;
      }
      if (!axis.endpoint || axis.job_id != setpoint.job_id()) return;
      axis.endpoint->begin_iteration(setpoint.iteration(), setpoint.start_position_m());
      const sim::AxisSample sample = axis.endpoint->sample();
      feedback.cycle(0);
      feedback.kind(netmc::dds::FEEDBACK_SAMPLE);
      feedback.position_m(sample.measured_m);
      feedback.true_position_m(sample.true_position_m);
      feedback.sample_time_s(0.0);
      break;
    }
    case netmc::dds::SETPOINT_COMMAND: {
      if (!axis.endpoint || axis.job_id != setpoint.job_id()) return;
      axis.endpoint->submit_setpoint(setpoint.send_time_s(), setpoint.cycle(), setpoint.command());
      const std::uint64_t next = setpoint.cycle() + 1;
      if (next >= axis.cycles) {
        feedback.cycle(next);
        feedback.kind(netmc::dds::FEEDBACK_FINAL);
        break;
      }
      const double next_time = static_cast<double>(next) * axis.sample_period_s;
      for (const auto& a : axis.endpoint->advance_to(next_time)) {
        netmc::dds::AppliedSetpoint applied;
        applied.cycle(a.sequence);
        applied.send_time_s(a.send_time_s);
        applied.arrival_time_s(a.arrival_time_s);
        feedback.applied().push_back(applied);
      }
      const sim::AxisSample sample = axis.endpoint->sample();
      feedback.cycle(next);
      feedback.kind(netmc::dds::FEEDBACK_SAMPLE);
      feedback.position_m(sample.measured_m);
      feedback.true_position_m(sample.true_position_m);
      feedback.sample_time_s(next_time);
      break;
    }
    case netmc::dds::SETPOINT_END_ITERATION:
      if (!axis.endpoint || axis.job_id != setpoint.job_id()) return;
      feedback.cycle(setpoint.cycle());
      feedback.kind(netmc::dds::FEEDBACK_FINAL);
      break;
    case netmc::dds::SETPOINT_END_JOB:
      if (axis.job_id == setpoint.job_id()) axis.endpoint.reset();
      return;
  }
  fill_counters(feedback, *axis.endpoint);
  feedback_writer_->write(&feedback);
}

}  // namespace netmc::axis
