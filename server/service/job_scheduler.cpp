#include "server/service/job_scheduler.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "plant/plant_catalog.hpp"
#include "server/job/job_builder.hpp"
#include "server/realtime/realtime_scheduling.hpp"
#include "server/service/error_response.hpp"
#include "server/service/job_admission.hpp"

namespace netmc::service {
namespace {

// The unit of a job's commands, for the console's plots: a catalogue plant's input unit. A file
// plant's (FMU, plugin) is the axis nodes' to read: the server reads no file a job names.
std::string command_unit(const std::string& plant_name) {
  try {
    return plant::is_file_plant(plant_name) ? "input" : plant::plant_input_unit(plant_name);
  } catch (const std::invalid_argument&) {
    return "input";
  }
}

}  // namespace

JobScheduler::JobScheduler(JobRegistry& registry, JobExecutor& executor, const JobServiceOptions& options)
    : registry_(registry), executor_(executor), options_(options) {
  if (options_.store) {
    std::lock_guard lock(registry_.mutex());
    for (const auto& job : registry_.restore_from_store()) {
      queued_spec_bytes_ += job->spec_bytes;
      queue_.push_back(job);
    }
  }
  scheduler_ = std::thread([this] { schedule(); });
  validator_ = std::thread([this] { validate(); });
}

JobScheduler::~JobScheduler() { stop(); }

void JobScheduler::stop() {
  {
    std::lock_guard lock(registry_.mutex());
    stopping_ = true;
    for (auto& [id, job] : registry_.jobs()) {
      job->cancel_reason = "the server is shutting down";
      job->cancel.store(true);
    }
  }
  wake_.notify_all();
  if (validator_.joinable()) validator_.join();
  if (scheduler_.joinable()) scheduler_.join();  // it joins every job thread before it returns
}

std::optional<std::string> JobScheduler::submit(const std::shared_ptr<management::Peer>& session,
                                                const netmc::v1::Request& request) {
  const std::size_t spec_bytes = request.submit().spec().ByteSizeLong();
  std::lock_guard lock(registry_.mutex());
  if (queue_.size() + submissions_.size() >= options_.max_queued_jobs) {
    return "submit: the server's queue is full (" + std::to_string(options_.max_queued_jobs) +
           " jobs waiting); try again later";
  }
  if (queued_spec_bytes_ + spec_bytes > options_.max_queued_spec_bytes) {
    return fmt::format("submit: the jobs waiting hold {:.1f} MiB of specs and this one {:.1f} MiB, beyond the "
                       "server's {:.0f} MiB; try again when the queue is shorter",
                       static_cast<double>(queued_spec_bytes_) / 1048576.0, static_cast<double>(spec_bytes) / 1048576.0,
                       static_cast<double>(options_.max_queued_spec_bytes) / 1048576.0);
  }
  queued_spec_bytes_ += spec_bytes;
  submissions_.push_back({session, request});
  wake_.notify_all();
  return std::nullopt;
}

bool JobScheduler::drop_if_queued(const std::shared_ptr<Job>& job) {
  const auto queued = std::find(queue_.begin(), queue_.end(), job);
  if (queued == queue_.end()) return false;
  queue_.erase(queued);
  end_queued(job, job->cancel_reason);
  spdlog::info("job {} cancelled while queued", job->id);
  wake_.notify_all();
  return true;
}

void JobScheduler::validate() {
  // Checking a client's spec can take long (a delay trace of 500 000 samples): it runs on the
  // normal scheduler, never against a running job's threads.
  realtime::leave_realtime_scheduling();
  realtime::name_this_thread("validate");
  std::unique_lock lock(registry_.mutex());
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || !submissions_.empty(); });
    if (stopping_) return;
    const Submission submission = std::move(submissions_.front());
    submissions_.pop_front();
    lock.unlock();
    admit(submission);  // the spec is checked (and its work bounded) off the I/O thread
    lock.lock();
  }
}

void JobScheduler::admit(const Submission& submission) {
  const auto& request = submission.request;
  const auto& session = submission.session;
  netmc::v1::JobSpec spec = request.submit().spec();
  const std::size_t spec_bytes = spec.ByteSizeLong();  // as submit() counted it
  const auto refuse = [&](const std::string& message) {
    {
      std::lock_guard lock(registry_.mutex());
      queued_spec_bytes_ -= spec_bytes;
    }
    session->send(error_response(request.request_id(), message));
  };
  job::apply_defaults(spec);
  try {
    job::reject_file_references(spec);  // the server opens no path a client names
    job::build_contour_job(spec, options_.build_options());  // every field checked before the job is queued
  } catch (const std::exception& error) {
    refuse(error.what());
    return;
  }
  // The axes get the spec in one DDS sample: a larger one would fail when the job starts.
  if (const std::size_t bytes = spec.ByteSizeLong(); bytes > netmc::dds::kMaxJobSpec) {
    refuse(fmt::format("submit: the job spec takes {} bytes, more than the {} its axis nodes take (an inline delay "
                       "trace of 1 000 000 samples alone takes 8 MB: shorten it to about 500 000)",
                       bytes, netmc::dds::kMaxJobSpec));
    return;
  }
  auto job = std::make_shared<Job>();
  job->axes = job::axis_names(spec);
  job->spec = spec;
  job->spec_bytes = spec_bytes;
  job->session = session;
  job->request_id = request.request_id();
  job->keep_after_disconnect = request.submit().keep_after_disconnect();
  job->owner = session->name();
  try {
    job->cancel_token = management::AccessToken::random();
  } catch (const std::exception& error) {
    refuse(std::string("submit: no cancel token for the job: ") + error.what());
    return;
  }
  job->accepted_unix_s = JobRegistry::unix_now_s();
  const std::string label = spec.name().empty() ? spec.controller().name() : spec.name();
  std::optional<std::uint64_t> stored_id;
  if (options_.store) {
    // Accepted only once on disk: a crash after the client hears "accepted" loses nothing.
    store::StoredJob stored;
    stored.label = label;
    stored.owner = job->owner;
    stored.spec = spec.SerializeAsString();
    stored.iterations_total = spec.iterations();
    stored.keep_after_disconnect = job->keep_after_disconnect;
    try {
      stored_id = options_.store->accept(stored);
    } catch (const store::StoreError& error) {
      refuse(std::string("submit: not accepted: ") + error.what() +
             "; the server accepts no job until its job store can be written (--state-dir)");
      return;
    }
  }
  std::lock_guard lock(registry_.mutex());
  if (stopping_) return;
  registry_.add(job, stored_id);
  job->status.set_job_id(job->id);
  job->status.set_state("queued");
  job->status.set_iterations_total(spec.iterations());
  job->status.set_label(label);
  job->status.set_command_unit(command_unit(spec.plant()));
  session->hold();  // not idle while its job is queued or running
  // Acknowledge before the worker can see the job, so "accepted" precedes its updates.
  netmc::v1::Response response;
  response.set_request_id(request.request_id());
  response.mutable_accepted()->set_job_id(job->id);
  response.mutable_accepted()->set_cancel_token(job->cancel_token->value());
  session->send(response);
  queue_.push_back(job);
  spdlog::info("job {} accepted: {}, {} iterations on axes {}", job->id, job->status.label(), spec.iterations(),
               fmt::join(job->axes, ","));
  wake_.notify_all();
}

void JobScheduler::tend_jobs() {
  const auto gone = [](const Job& job) {
    const auto session = job.session.lock();
    return !job.keep_after_disconnect && (!session || !session->open());
  };
  for (auto it = queue_.begin(); it != queue_.end();) {
    const auto job = *it;
    if (!gone(*job)) {
      ++it;
      continue;
    }
    spdlog::info("job {} dropped from the queue: its client disconnected", job->id);
    end_queued(job, "its client disconnected");
    it = queue_.erase(it);
  }
  for (const auto& [id, thread] : running_) {
    Job& job = *registry_.jobs().at(id);
    if (!job.cancel.load() && gone(job)) {
      job.cancel_reason = "its client disconnected";
      job.cancel.store(true);
    }
  }
  registry_.forget_beyond_history();
}

void JobScheduler::end_queued(const std::shared_ptr<Job>& job, const std::string& reason) {
  queued_spec_bytes_ -= job->spec_bytes;
  registry_.end_unrun(job, reason);
}

void JobScheduler::schedule() {
  realtime::name_this_thread("schedule");
  std::unique_lock lock(registry_.mutex());
  while (true) {
    for (auto& thread : finished_) thread.join();
    finished_.clear();
    if (stopping_) break;
    std::vector<std::vector<std::string>> queued;
    for (const auto& job : queue_) queued.push_back(job->axes);
    const auto start = admissible_jobs(queued, busy_axes_, running_.size(), options_.max_running_jobs);
    std::vector<std::shared_ptr<Job>> starting;
    for (const std::size_t index : start) starting.push_back(queue_[index]);
    for (const auto& job : starting) {
      queue_.erase(std::find(queue_.begin(), queue_.end(), job));
      queued_spec_bytes_ -= job->spec_bytes;
      busy_axes_.insert(job->axes.begin(), job->axes.end());
      job->status.set_state("running");
      job->status.clear_waiting_for();
      spdlog::info("job {} running on axes {} ({} running, {} queued)", job->id, fmt::join(job->axes, ","),
                   running_.size() + 1,
                   queue_.size());
      running_.emplace(job->id, std::thread([this, job] {
        realtime::name_this_thread(fmt::format("job {}", job->id));
        executor_.run(job);
        finish(job);
      }));
    }
    // What each waiting job waits behind, for `netmc status`.
    std::vector<JobAxes> running_axes, queued_before;
    for (const auto& [id, thread] : running_) running_axes.push_back({id, registry_.jobs().at(id)->axes});
    for (const auto& job : queue_) {
      job->status.set_waiting_for(waiting_for(job->axes, running_axes, queued_before, options_.max_running_jobs));
      queued_before.push_back({job->id, job->axes});
    }
    tend_jobs();
    // Woken by submissions and ends of jobs; every quarter second anyway, to see closed clients.
    wake_.wait_for(lock, std::chrono::milliseconds(250));
  }
  // Stopping: the jobs were cancelled; wait for their threads.
  while (!running_.empty()) {
    wake_.wait(lock);
    for (auto& thread : finished_) thread.join();
    finished_.clear();
  }
}

void JobScheduler::finish(const std::shared_ptr<Job>& job) {
  if (const auto session = job->session.lock()) session->release();
  {
    std::lock_guard lock(registry_.mutex());
    registry_.mark_ended(job->id);
    job->spec = netmc::v1::JobSpec();  // an ended job keeps its status and result, not its spec
    for (const auto& axis : job->axes) busy_axes_.erase(axis);
    const auto it = running_.find(job->id);
    finished_.push_back(std::move(it->second));
    running_.erase(it);
  }
  wake_.notify_all();
}

}  // namespace netmc::service
