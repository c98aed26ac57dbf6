#pragma once
// The jobs netmc-server holds: their ids, states, iterations so far, ends, watchers and the
// history of ended jobs, with the service's totals. Its mutex is the job service's one lock;
// the scheduler's queue shares it. See docs/architecture.md, Threads and queues.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "idl/management.pb.h"
#include "server/management/access_token.hpp"
#include "server/management/management_server.hpp"
#include "server/service/job_service_options.hpp"
#include "server/sim/iteration_metrics.hpp"
#include "server/store/job_store.hpp"

namespace netmc::service {

// What the service has done since it started (netmc-server's /metrics).
struct ServiceTotals {
  std::uint64_t iterations = 0;
  std::uint64_t deadline_misses = 0;
  std::uint64_t lost_feedback = 0;
  std::uint64_t lost_setpoints = 0;
  std::uint64_t forged_samples = 0;  // feedback or axis events from participants not hosting the axis
  // The loop delay: quantiles of the latest ended iteration, and sum and count over all.
  double tau_p50_s = 0.0, tau_p99_s = 0.0, tau_max_s = 0.0;
  double tau_sum_s = 0.0;
  std::uint64_t tau_count = 0;
  std::map<std::string, std::uint64_t> jobs_by_state;  // of the jobs the service still holds
  std::uint64_t failed_iterations = 0;  // iterations a job failed during (not in the counts above)
  // The latest iteration of each job the service holds that has one.
  struct LastIteration {
    std::uint64_t job_id = 0;
    std::string label;
    std::uint32_t iteration = 0;
    double e_max_m = 0.0;
  };
  std::vector<LastIteration> last_iterations;  // filled by totals()
};

// A connection following a job (netmc watch); the job keeps it from idling out till it ends.
struct Watcher {
  std::weak_ptr<management::Peer> session;
  std::uint64_t request_id = 0;
};

// One job of the server. Fields set before the job is in the registry are read freely; those
// marked "under the lock" change later and are read and written under JobRegistry::mutex().
struct Job {
  std::uint64_t id = 0;
  netmc::v1::JobSpec spec;  // cleared under the lock when the job ends
  std::weak_ptr<management::Peer> session;
  std::uint64_t request_id = 0;
  netmc::v1::JobStatus status;  // under the lock
  std::atomic<bool> cancel{false};
  std::string cancel_reason;  // set with `cancel`, under the lock
  std::vector<std::string> axes;
  bool keep_after_disconnect = false;
  std::string owner;                // who submitted it
  // Shown by another connection to cancel the job; none for a job restored from the store.
  std::optional<management::AccessToken> cancel_token;
  double accepted_unix_s = 0.0;
  double ended_unix_s = 0.0;        // under the lock
  std::size_t spec_bytes = 0;       // counted against max_queued_spec_bytes while it waits
  // Under the lock: the iterations reported so far (until it ends), its end (once it has ended;
  // a job dropped from the queue has none) and who follows it.
  std::vector<netmc::v1::IterationMetrics> iterations;
  std::optional<netmc::v1::JobFinished> finished;
  std::vector<Watcher> watchers;
};

class JobRegistry {
 public:
  explicit JobRegistry(const JobServiceOptions& options) : options_(options) {}
  JobRegistry(const JobRegistry&) = delete;
  JobRegistry& operator=(const JobRegistry&) = delete;

  // The one lock of the job service: every job's fields marked "under the lock", this
  // registry's maps and totals, and the scheduler's submissions, queue, busy axes and threads
  // (one lock, so that a cancel takes a job out of the queue and ends it at once).
  std::mutex& mutex() const { return mutex_; }

  static double unix_now_s();

  // Under mutex(): the job `id`, or null (never submitted, or forgotten beyond the history).
  std::shared_ptr<Job> find(std::uint64_t id) const;
  // Under mutex(): every job held, by id.
  const std::map<std::uint64_t, std::shared_ptr<Job>>& jobs() const { return jobs_; }
  // Under mutex(): a new job gets its id (the store's, if given) and is held.
  void add(const std::shared_ptr<Job>& job, std::optional<std::uint64_t> stored_id);
  // Under mutex(): the job has ended; the oldest ended jobs beyond the history are forgotten.
  void mark_ended(std::uint64_t id);
  void forget_beyond_history();

  // Under mutex(): a new watcher of `job` gets its status and the iterations so far (and its end,
  // if it has ended); refused with a reason if the job has too many watchers already.
  void start_watch(Job& job, const std::shared_ptr<management::Peer>& session, std::uint64_t request_id);
  // Under mutex(): a queued job ends without running (cancelled, its client gone): its status at
  // once; kept in the store, then its watchers and submitter hear of it.
  void end_unrun(const std::shared_ptr<Job>& job, const std::string& reason);

  // The submitter of `job` gets `response` (no lock needed: the session is thread-safe).
  static void reply(const Job& job, netmc::v1::Response response);
  // Each of the following takes mutex().
  // A running job's iteration: kept in the store (with one), then to its watchers and its
  // submitter (on the store's writer; while the store cannot be written they wait).
  void report_iteration(const std::shared_ptr<Job>& job, netmc::v1::Response update);
  // A running job's iteration counted in the totals; `job_cycles` its cycles per iteration.
  void count_iteration(Job& job, const sim::IterationMetrics& metrics, std::uint64_t job_cycles);
  void count_forged_samples(std::uint64_t forged);
  // A job failed during an iteration: that iteration never ended, and no metrics of it came.
  void count_failed_iteration();
  // What a running job waits for before its first cycle, for `netmc status` ("" none).
  void set_waiting_for(Job& job, const std::string& what);
  std::string cancel_reason(const Job& job) const;
  // The job has ended with `finished`: kept in the store (with one), then its status, its
  // watchers and its submitter. While the store cannot be written they wait (the write is tried
  // again until it is kept) and the job's status says what it waits for: no one is told of an end
  // a restart would not find.
  void conclude(const std::shared_ptr<Job>& job, const netmc::v1::JobFinished& finished);
  ServiceTotals totals() const;
  // netmc jobs: the history, from the store (or from memory without one).
  netmc::v1::JobList list_jobs(const netmc::v1::ListJobs& filter) const;

  // Under mutex(), before the threads start: the store's latest ended jobs and its unfinished
  // ones (a running one failed by the restart). Returns the queued ones to queue again, in order.
  std::vector<std::shared_ptr<Job>> restore_from_store();

 private:
  // A running job's iteration, kept: to its watchers, then its submitter.
  void deliver_iteration(const std::shared_ptr<Job>& job, netmc::v1::Response update);
  // Under mutex(): `job` has ended with `finished`: each watcher gets it and is let go.
  void end_watches(Job& job, const netmc::v1::JobFinished& finished);
  // Under mutex(), with a store: `finished` is written, then `tell` runs (on the store's writer,
  // without the lock). Meanwhile the job's status says what it waits for (and why, if known).
  void keep_end(Job& job, const netmc::v1::JobFinished& finished, std::function<void()> tell);
  // Under mutex(): `job` has ended with `finished`: its status.
  void record_end(Job& job, const netmc::v1::JobFinished& finished);
  // Takes mutex(): record_end(), its watchers, then its submitter hear of it.
  void tell_end(const std::shared_ptr<Job>& job, const netmc::v1::JobFinished& finished);

  const JobServiceOptions& options_;
  mutable std::mutex mutex_;
  std::map<std::uint64_t, std::shared_ptr<Job>> jobs_;  // under mutex_
  std::deque<std::uint64_t> ended_;                     // under mutex_: ended job ids, oldest first
  std::uint64_t next_id_ = 1;                           // under mutex_ (without a store)
  ServiceTotals totals_;                                // under mutex_ (jobs_by_state filled by totals())
};

}  // namespace netmc::service
