#include "server/service/job_service.hpp"

#include <iostream>
#include <set>

#include "dds_typesPubSubTypes.h"
#include "server/dds/topics.hpp"
#include "server/job/job_builder.hpp"
#include "server/service/lockstep_dds_runner.hpp"
#include "server/service/realtime_dds_runner.hpp"

namespace netmc::service {
namespace {

netmc::v1::Response error_response(std::uint64_t request_id, const std::string& message) {
  netmc::v1::Response response;
  response.set_request_id(request_id);
  response.mutable_error()->set_message(message);
  return response;
}

const char* health_name(netmc::dds::NodeHealth health) {
  switch (health) {
    case netmc::dds::NODE_IDLE: return "idle";
    case netmc::dds::NODE_RUNNING: return "running";
    case netmc::dds::NODE_HOLD: return "hold";
    case netmc::dds::NODE_FAULT: return "fault";
  }
  return "unknown";
}

}  // namespace

JobService::JobService(dds::DdsContext& context, NodeDirectory& nodes, JobServiceOptions options)
    : context_(context),
      nodes_(nodes),
      options_(options),
      setpoints_(context.writer(context.topic<netmc::dds::SetpointPubSubType>(dds::kSetpointTopic),
                                dds::Delivery::control)),
      feedback_(context.reader(context.topic<netmc::dds::FeedbackPubSubType>(dds::kFeedbackTopic),
                               dds::Delivery::control)),
      iteration_logs_(context.writer(
          context.topic<netmc::dds::IterationLogPubSubType>(dds::kIterationLogTopic),
          dds::Delivery::log)),
      worker_([this] { work(); }) {}

JobService::~JobService() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    for (auto& [id, job] : jobs_) job->cancel.store(true);
  }
  wake_.notify_all();
  worker_.join();
}

void JobService::handle(const std::shared_ptr<management::Session>& session,
                        const netmc::v1::Request& request) {
  netmc::v1::Response response;
  response.set_request_id(request.request_id());
  switch (request.kind_case()) {
    case netmc::v1::Request::kSubmit: {
      netmc::v1::JobSpec spec = request.submit().spec();
      job::apply_defaults(spec);
      try {
        job::build_contour_job(spec);  // every field checked before the job is queued
      } catch (const std::exception& error) {
        session->send(error_response(request.request_id(), error.what()));
        return;
      }
      auto job = std::make_shared<Job>();
      job->spec = spec;
      job->session = session;
      job->request_id = request.request_id();
      std::lock_guard lock(mutex_);
      job->id = next_id_++;
      job->status.set_job_id(job->id);
      job->status.set_state("queued");
      job->status.set_iterations_total(spec.iterations());
      job->status.set_label(spec.name().empty() ? spec.controller().name() : spec.name());
      jobs_[job->id] = job;
      // Acknowledge before the worker can see the job, so "accepted" precedes its updates.
      response.mutable_accepted()->set_job_id(job->id);
      session->send(response);
      queue_.push_back(job);
      wake_.notify_one();
      return;
    }
    case netmc::v1::Request::kCancel: {
      std::lock_guard lock(mutex_);
      const auto it = jobs_.find(request.cancel().job_id());
      if (it == jobs_.end()) {
        session->send(error_response(request.request_id(),
                                     "cancel: no job " + std::to_string(request.cancel().job_id())));
        return;
      }
      it->second->cancel.store(true);
      *response.mutable_status()->add_jobs() = it->second->status;
      break;
    }
    case netmc::v1::Request::kStatus: {
      std::lock_guard lock(mutex_);
      for (const auto& [id, job] : jobs_) {
        if (request.status().job_id() == 0 || request.status().job_id() == id) {
          *response.mutable_status()->add_jobs() = job->status;
        }
      }
      break;
    }
    case netmc::v1::Request::kNodes: {
      const auto now = std::chrono::steady_clock::now();
      for (const auto& record : nodes_.nodes()) {
        auto& info = *response.mutable_nodes()->add_nodes();
        info.set_node(record.status.node());
        for (const auto id : record.status.axis_ids()) info.add_axes(id == 0 ? "x" : id == 1 ? "y" : std::to_string(id));
        info.set_plant(record.status.plant());
        info.set_health(std::string(health_name(record.status.health())) +
                        (record.status.detail().empty() ? "" : ": " + record.status.detail()));
        info.set_last_seen_s(std::chrono::duration<double>(now - record.last_seen).count());
        info.set_clock(record.status.clock());
      }
      break;
    }
    case netmc::v1::Request::KIND_NOT_SET:
      session->send(error_response(request.request_id(), "request: empty (expected submit, cancel, status or nodes)"));
      return;
  }
  session->send(response);
}

void JobService::reply(Job& job, netmc::v1::Response response) {
  response.set_request_id(job.request_id);
  if (auto session = job.session.lock()) session->send(response);
}

void JobService::work() {
  while (true) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      job = queue_.front();
      queue_.pop_front();
      job->status.set_state("running");
    }
    run(*job);
  }
}

void JobService::run(Job& job) {
  netmc::v1::Response finished;
  auto& done = *finished.mutable_finished();
  done.set_job_id(job.id);
  std::string state = "done";
  try {
    if (job.cancel.load()) throw JobFailure("cancelled before it started");
    // The job needs a node for each axis, hosting the job's plant.
    std::set<std::string> node_names;
    for (std::uint32_t axis = 0; axis < 2; ++axis) {
      const auto deadline = std::chrono::steady_clock::now() + options_.discovery_timeout;
      std::optional<NodeRecord> node;
      while (!(node = nodes_.node_for_axis(axis, std::chrono::seconds(3))) &&
             std::chrono::steady_clock::now() < deadline && !job.cancel.load()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      if (!node) {
        throw JobFailure(std::string("no axis node for axis ") + (axis == 0 ? "x" : "y") +
                         " was discovered within " +
                         std::to_string(options_.discovery_timeout.count()) + " ms");
      }
      const std::string clock = job.spec.clock().empty() ? "lockstep" : job.spec.clock();
      if (node->status.clock() != clock) {
        throw JobFailure("node " + node->status.node() + " runs the " + node->status.clock() +
                         " clock but the job needs " + clock);
      }
      if (node->status.plant() != job.spec.plant()) {
        throw JobFailure("node " + node->status.node() + " hosts plant '" + node->status.plant() +
                         "' but the job needs '" + job.spec.plant() + "'");
      }
      node_names.insert(node->status.node());
    }
    if (!dds::wait_for_readers(setpoints_, static_cast<int>(node_names.size()),
                               options_.discovery_timeout)) {
      throw JobFailure("axis nodes were discovered but their setpoint readers did not match");
    }
    const auto on_iteration = [&](const sim::IterationRecord& record) {
      const auto metrics = job::to_proto(record.metrics);
      *done.mutable_result()->add_iterations() = metrics;
      {
        std::lock_guard lock(mutex_);
        job.status.set_iterations_done(static_cast<std::uint32_t>(record.metrics.iteration));
      }
      netmc::v1::Response update;
      auto& iteration = *update.mutable_iteration();
      iteration.set_job_id(job.id);
      iteration.set_total_iterations(job.spec.iterations());
      *iteration.mutable_metrics() = metrics;
      reply(job, update);
    };
    const JobChannels channels{setpoints_, &feedback_, iteration_logs_};
    if (job.spec.clock() == "realtime") {
      RealtimeDdsRunner runner(channels, job.spec, job.id, options_.axis_timeout,
                               options_.missed_cycles_limit);
      *done.mutable_result() = job::describe_run(job.spec, runner.controller_description());
      runner.run(on_iteration, job.cancel);
    } else {
      LockstepDdsRunner runner(channels, job.spec, job.id, options_.axis_timeout);
      *done.mutable_result() = job::describe_run(job.spec, runner.controller_description());
      runner.run(on_iteration, job.cancel);
    }
    if (job.cancel.load()) state = "cancelled";
  } catch (const std::exception& error) {
    state = job.cancel.load() ? "cancelled" : "failed";
    done.set_error(error.what());
    std::cerr << "netmc-server: job " << job.id << " " << state << ": " << error.what() << std::endl;
  }
  done.set_state(state);
  {
    std::lock_guard lock(mutex_);
    job.status.set_state(state);
    job.status.set_error(done.error());
  }
  reply(job, finished);
}

}  // namespace netmc::service
