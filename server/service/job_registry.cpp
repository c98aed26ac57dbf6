#include "server/service/job_registry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "server/job/job_builder.hpp"
#include "server/service/error_response.hpp"
#include "server/store/job_list.hpp"

namespace netmc::service {

double JobRegistry::unix_now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

std::shared_ptr<Job> JobRegistry::find(std::uint64_t id) const {
  const auto it = jobs_.find(id);
  return it == jobs_.end() ? nullptr : it->second;
}

void JobRegistry::add(const std::shared_ptr<Job>& job, std::optional<std::uint64_t> stored_id) {
  job->id = stored_id ? *stored_id : next_id_++;
  jobs_[job->id] = job;
}

void JobRegistry::mark_ended(std::uint64_t id) { ended_.push_back(id); }

void JobRegistry::forget_beyond_history() {
  while (ended_.size() > options_.job_history) {
    jobs_.erase(ended_.front());
    ended_.pop_front();
  }
}

void JobRegistry::reply(const Job& job, netmc::v1::Response response) {
  response.set_request_id(job.request_id);
  if (auto session = job.session.lock()) session->send(response);
}

void JobRegistry::start_watch(Job& job, const std::shared_ptr<management::Peer>& session,
                              std::uint64_t request_id) {
  std::erase_if(job.watchers, [](const Watcher& watcher) {
    const auto other = watcher.session.lock();
    return !other || !other->open();
  });
  if (job.watchers.size() >= options_.max_watchers_per_job) {
    session->send(error_response(request_id, "watch: job " + std::to_string(job.id) + " has " +
                                                 std::to_string(job.watchers.size()) +
                                                 " watchers already (the server's limit)"));
    return;
  }
  netmc::v1::Response response;
  response.set_request_id(request_id);
  *response.mutable_status()->add_jobs() = job.status;
  session->send(response);
  const auto send_iteration = [&](const netmc::v1::IterationMetrics& metrics) {
    netmc::v1::Response update;
    update.set_request_id(request_id);
    update.mutable_iteration()->set_job_id(job.id);
    update.mutable_iteration()->set_total_iterations(job.status.iterations_total());
    *update.mutable_iteration()->mutable_metrics() = metrics;
    session->send(update);
  };
  const std::string& state = job.status.state();
  if (state == "queued" || state == "running") {
    for (const auto& metrics : job.iterations) send_iteration(metrics);
    job.watchers.push_back({session, request_id});
    session->hold();  // not idle while it waits for the job
    return;
  }
  // Ended. A job dropped from the queue never ran: its end is its status.
  netmc::v1::JobFinished finished;
  if (job.finished) {
    finished = *job.finished;
  } else {
    finished.set_job_id(job.id);
    finished.set_state(state);
    finished.set_error(job.status.error());
  }
  for (const auto& metrics : finished.result().iterations()) send_iteration(metrics);
  netmc::v1::Response end;
  end.set_request_id(request_id);
  *end.mutable_finished() = std::move(finished);
  session->send(end);
}

void JobRegistry::end_watches(Job& job, const netmc::v1::JobFinished& finished) {
  for (const auto& watcher : job.watchers) {
    const auto session = watcher.session.lock();
    if (!session) continue;
    netmc::v1::Response end;
    end.set_request_id(watcher.request_id);
    *end.mutable_finished() = finished;
    session->send(end);
    session->release();
  }
  job.watchers.clear();
  job.iterations.clear();  // the end carries them
}

void JobRegistry::end_unrun(const std::shared_ptr<Job>& job, const std::string& reason) {
  job->spec = netmc::v1::JobSpec();
  netmc::v1::JobFinished finished;
  finished.set_job_id(job->id);
  finished.set_state("cancelled");
  finished.set_error(reason);
  // Its status at once (the answer to netmc cancel shows it); its followers once it is kept.
  record_end(*job, finished);
  ended_.push_back(job->id);
  auto tell = [this, job, finished](bool locked) {
    {
      std::unique_lock lock(mutex_, std::defer_lock);
      if (!locked) lock.lock();
      job->status.clear_waiting_for();
      end_watches(*job, finished);
    }
    netmc::v1::Response end;
    *end.mutable_finished() = finished;
    reply(*job, end);
    if (const auto submitter = job->session.lock()) submitter->release();
  };
  if (!options_.store) {
    tell(true);
    return;
  }
  keep_end(*job, finished, [tell] { tell(false); });
}

void JobRegistry::keep_end(Job& job, const netmc::v1::JobFinished& finished, std::function<void()> tell) {
  // Cleared once it is kept and told (at once, unless the store cannot be written). A cancelled
  // queued job's status shows its reason unless the store is known to fail.
  const auto problem = options_.store->problem();
  if (job.status.state() != finished.state() || !problem.empty()) {
    job.status.set_waiting_for("its end (" + finished.state() + ") to be written to the job store" +
                               (problem.empty() ? std::string()
                                                : ", which cannot be written now (" + problem + "); tried again until it is"));
  }
  options_.store->ended(job.id, finished.state(), finished.error(), finished.SerializeAsString(), std::move(tell));
}

void JobRegistry::report_iteration(const std::shared_ptr<Job>& job, netmc::v1::Response update) {
  if (!options_.store) {
    deliver_iteration(job, std::move(update));
    return;
  }
  const auto& metrics = update.iteration().metrics();
  options_.store->iteration(job->id, metrics.iteration(), metrics.SerializeAsString(),
                            [this, job, update]() mutable { deliver_iteration(job, std::move(update)); });
}

void JobRegistry::deliver_iteration(const std::shared_ptr<Job>& job, netmc::v1::Response update) {
  {
    std::lock_guard lock(mutex_);
    job->iterations.push_back(update.iteration().metrics());
    for (const auto& watcher : job->watchers) {
      if (const auto session = watcher.session.lock()) {
        update.set_request_id(watcher.request_id);
        session->send(update);
      }
    }
  }
  reply(*job, update);
}

void JobRegistry::count_iteration(Job& job, const sim::IterationMetrics& metrics, std::uint64_t job_cycles) {
  std::lock_guard lock(mutex_);
  ++totals_.iterations;
  totals_.deadline_misses += metrics.deadline_misses;
  totals_.lost_feedback += metrics.lost_feedback;
  totals_.lost_setpoints += metrics.lost_setpoints;
  totals_.tau_p50_s = metrics.tau_p50_s;
  totals_.tau_p99_s = metrics.tau_p99_s;
  totals_.tau_max_s = metrics.tau_max_s;
  const std::uint64_t delays = job_cycles > metrics.lost_setpoints ? job_cycles - metrics.lost_setpoints : 0;
  totals_.tau_sum_s += metrics.tau_mean_s * static_cast<double>(delays);
  totals_.tau_count += delays;
  job.status.set_iterations_done(static_cast<std::uint32_t>(metrics.iteration));
}

void JobRegistry::count_failed_iteration() {
  std::lock_guard lock(mutex_);
  ++totals_.failed_iterations;
}

void JobRegistry::count_forged_samples(std::uint64_t forged) {
  std::lock_guard lock(mutex_);
  totals_.forged_samples += forged;
}

void JobRegistry::set_waiting_for(Job& job, const std::string& what) {
  std::lock_guard lock(mutex_);
  if (what.empty()) {
    job.status.clear_waiting_for();
  } else {
    job.status.set_waiting_for(what);
  }
}

std::string JobRegistry::cancel_reason(const Job& job) const {
  std::lock_guard lock(mutex_);
  return job.cancel_reason;
}

void JobRegistry::conclude(const std::shared_ptr<Job>& job, const netmc::v1::JobFinished& finished) {
  if (!options_.store) {
    tell_end(job, finished);
    return;
  }
  std::lock_guard lock(mutex_);
  keep_end(*job, finished, [this, job, finished] { tell_end(job, finished); });
}

void JobRegistry::record_end(Job& job, const netmc::v1::JobFinished& finished) {
  job.status.set_state(finished.state());
  job.status.set_error(finished.error());
  job.status.clear_waiting_for();
  job.ended_unix_s = unix_now_s();
  job.finished = finished;
}

void JobRegistry::tell_end(const std::shared_ptr<Job>& job, const netmc::v1::JobFinished& finished) {
  {
    std::lock_guard lock(mutex_);
    record_end(*job, finished);
    end_watches(*job, finished);
  }
  netmc::v1::Response end;
  *end.mutable_finished() = finished;
  reply(*job, end);
}

ServiceTotals JobRegistry::totals() const {
  std::lock_guard lock(mutex_);
  ServiceTotals totals = totals_;
  for (const auto& [id, job] : jobs_) {
    ++totals.jobs_by_state[job->status.state()];
    const netmc::v1::IterationMetrics* last = nullptr;
    if (!job->iterations.empty()) {
      last = &job->iterations.back();
    } else if (job->finished && job->finished->result().iterations_size() > 0) {
      last = &job->finished->result().iterations(job->finished->result().iterations_size() - 1);
    }
    if (last) totals.last_iterations.push_back({id, job->status.label(), last->iteration(), last->e_max_m()});
  }
  return totals;
}

std::vector<std::shared_ptr<Job>> JobRegistry::restore_from_store() {
  const auto contents = options_.store->load(options_.job_history);
  const auto make_job = [this](const store::StoredJob& stored) {
    auto job = std::make_shared<Job>();
    job->id = stored.id;
    job->owner = stored.owner;
    job->accepted_unix_s = stored.accepted_unix_s;
    job->ended_unix_s = stored.ended_unix_s;
    // No connection outlived the restart: the job is the server's until it ends.
    job->keep_after_disconnect = true;
    job->status.set_job_id(stored.id);
    job->status.set_state(stored.state);
    job->status.set_error(stored.error);
    job->status.set_label(stored.label);
    job->status.set_iterations_total(stored.iterations_total);
    job->status.set_iterations_done(stored.iterations_done);
    jobs_[job->id] = job;
    return job;
  };
  for (const auto& stored : contents.ended) {
    auto job = make_job(stored);
    netmc::v1::JobFinished finished;
    if (finished.ParseFromString(stored.finished)) job->finished = std::move(finished);
    ended_.push_back(job->id);
  }
  std::vector<std::shared_ptr<Job>> requeued;
  std::size_t failed = 0;
  for (const auto& stored : contents.unfinished) {
    auto job = make_job(stored);
    if (stored.state == "running") {
      // What it finished is kept; the iteration under way when the server stopped is lost.
      netmc::v1::JobFinished finished;
      finished.set_job_id(job->id);
      finished.set_state("failed");
      finished.set_error("server restarted during iteration " + std::to_string(stored.iterations.size() + 1));
      (void)finished.mutable_result()->ParseFromString(stored.result_header);
      for (const auto& iteration : stored.iterations) {
        (void)finished.mutable_result()->add_iterations()->ParseFromString(iteration.metrics);
      }
      job->status.set_state("failed");
      job->status.set_error(finished.error());
      job->ended_unix_s = unix_now_s();
      job->finished = finished;
      ended_.push_back(job->id);
      options_.store->ended(job->id, "failed", finished.error(), finished.SerializeAsString());
      ++failed;
      continue;
    }
    const auto fail_stored = [&](const std::string& why) {
      job->status.set_state("failed");
      job->status.set_error(why);
      job->ended_unix_s = unix_now_s();
      options_.store->ended(job->id, "failed", why, {});
      ended_.push_back(job->id);
      ++failed;
    };
    if (!job->spec.ParseFromString(stored.spec)) {
      fail_stored("its stored spec cannot be read");
      continue;
    }
    // A stored spec is checked as a submitted one is (the store is a file anyone with access to
    // it may have edited): no path it names is opened, every field in range, its axes named.
    try {
      job::reject_file_references(job->spec);
      job::build_contour_job(job->spec, options_.build_options());
      job->axes = job::axis_names(job->spec);
    } catch (const std::exception& error) {
      fail_stored(std::string("its stored spec fails the checks of a submitted one: ") + error.what());
      continue;
    }
    job->spec_bytes = job->spec.ByteSizeLong();
    requeued.push_back(job);
  }
  spdlog::info("job store {}: {} ended jobs in memory, {} queued again, {} failed (by the restart, or their stored spec)",
               options_.store->file().string(), contents.ended.size(), requeued.size(), failed);
  return requeued;
}

netmc::v1::JobList JobRegistry::list_jobs(const netmc::v1::ListJobs& request) const {
  const auto filter = store::job_filter(request);
  std::vector<store::StoredJob> listed;
  if (options_.store) {
    // The store lags the memory by the writes still queued (a job that has just started, or
    // ended): a job the service still holds is listed as netmc status shows it.
    listed = options_.store->list(filter);
    std::lock_guard lock(mutex_);
    for (auto& row : listed) {
      const auto held = jobs_.find(row.id);
      if (held == jobs_.end()) continue;
      const auto& status = held->second->status;
      row.state = status.state();
      row.error = status.error();
      row.iterations_done = std::max(row.iterations_done, status.iterations_done());
    }
    std::erase_if(listed, [&filter](const store::StoredJob& row) {
      return !filter.state.empty() && row.state != filter.state;
    });
    return store::job_list(listed, true);
  }
  std::lock_guard lock(mutex_);
  for (auto it = jobs_.rbegin(); it != jobs_.rend() && listed.size() < filter.limit; ++it) {
    const Job& job = *it->second;
    const auto& status = job.status;
    if (!filter.state.empty() && status.state() != filter.state) continue;
    if (!filter.label_contains.empty() && status.label().find(filter.label_contains) == std::string::npos) continue;
    if (job.accepted_unix_s < filter.since_unix_s) continue;
    store::StoredJob row;
    row.id = job.id;
    row.label = status.label();
    row.state = status.state();
    row.error = status.error();
    row.owner = job.owner;
    row.accepted_unix_s = job.accepted_unix_s;
    row.ended_unix_s = job.ended_unix_s;
    row.iterations_done = status.iterations_done();
    row.iterations_total = status.iterations_total();
    listed.push_back(std::move(row));
  }
  return store::job_list(listed, false);
}

}  // namespace netmc::service
