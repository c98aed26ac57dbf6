#pragma once
// netmc-server's job service: accepts jobs over the management endpoint, runs them on the
// discovered axis nodes over DDS, streams each iteration's metrics back to the submitting client
// and keeps every job's status. Jobs on disjoint axes run at once, each on a thread of its own
// with DDS readers of its own (in its axes' partitions, so no job sees another's samples); a
// job waits in the queue only while one of its axes is busy, or the running-job limit is reached.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include "idl/management.pb.h"
#include "server/dds/dds_context.hpp"
#include "server/job/job_builder.hpp"
#include "server/management/management_server.hpp"
#include "server/service/clock_tracker.hpp"
#include "server/service/dds_job_messages.hpp"
#include "server/service/node_directory.hpp"
#include "server/sim/cycle_listener.hpp"
#include "server/store/job_store.hpp"

namespace netmc::service {

struct JobServiceOptions {
  std::chrono::milliseconds axis_timeout{2000};       // per lockstep exchange
  std::chrono::milliseconds discovery_timeout{10000}; // waiting for the nodes of a job
  std::chrono::milliseconds silence_limit{500};       // realtime: an axis silent this long fails
  dds::TimeBase time_base = dds::TimeBase::monotonic; // realtime jobs' schedule
  std::size_t max_running_jobs = 32;
  std::size_t max_queued_jobs = 256;                  // waiting for validation or for axes
  std::size_t job_history = 256;                      // ended jobs kept in memory for status and watch
  // Bytes of job specs waiting (for validation or for axes); a submit beyond is refused. A spec
  // may carry inline delay traces of megabytes.
  std::size_t max_queued_spec_bytes = std::size_t{256} << 20;
  std::size_t max_watchers_per_job = 16;              // netmc watch connections following one job
  // Realtime: for every axis to stand ready at an iteration's start (hardware is moved there).
  std::chrono::milliseconds positioning_timeout{60000};
  // An axis held by another server: how long a job waits for the hold to end (a node lets the
  // hold of a server it no longer hears from go after its hold lease, 10 s).
  std::chrono::milliseconds foreign_hold_wait{15000};
  // The server has an admin token: resetting an axis's fault needs it.
  bool admin_token_configured = false;
  // Controller plugins a job may name (netmc-server --allow-plugin), exact paths; none: no plugin.
  std::vector<std::string> allowed_plugins;
  // A live view of each job's cycles (the console): called when a job starts running; null or
  // unset: none.
  std::function<std::shared_ptr<sim::CycleListener>(std::uint64_t job_id)> live_cycles;
  // The persistent job store (netmc-server --state-dir); null: jobs live in memory only. When
  // set, a job is accepted only once it is on disk, a client hears of an iteration only once it
  // is kept, and the service starts with the store's queue and history.
  std::shared_ptr<store::JobStore> store;

  // How the server builds a job: the controller here (a plugin only if allowed), plants read
  // from files only on their axis nodes.
  job::JobBuildOptions build_options() const {
    job::JobBuildOptions build;
    build.load_plant_files = false;
    build.controller_plugins.allowed = allowed_plugins;
    return build;
  }
};

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
};

class JobService {
 public:
  JobService(dds::DdsContext& context, NodeDirectory& nodes, ClockTracker& clocks,
             JobServiceOptions options);
  ~JobService();
  JobService(const JobService&) = delete;
  JobService& operator=(const JobService&) = delete;

  // Called on the management endpoint's thread for every request; never blocks on a job spec
  // (submitted specs are checked on a thread of their own).
  // `admin`: the request showed the admin token (--admin-token-file): it may cancel any job;
  // otherwise only the connection that submitted a job may.
  void handle(const std::shared_ptr<management::Peer>& session, const netmc::v1::Request& request,
              bool admin = false);

  ServiceTotals totals() const;

 private:
  // netmc nodes's view of one node (also the answer to a reset).
  void fill_node_info(const NodeRecord& record, std::chrono::steady_clock::time_point now,
                      netmc::v1::NodeInfo& info) const;

  // A connection following a job (netmc watch); the job keeps it from idling out till it ends.
  struct Watcher {
    std::weak_ptr<management::Peer> session;
    std::uint64_t request_id = 0;
  };
  struct Job {
    std::uint64_t id = 0;
    netmc::v1::JobSpec spec;
    std::weak_ptr<management::Peer> session;
    std::uint64_t request_id = 0;
    netmc::v1::JobStatus status;
    std::atomic<bool> cancel{false};
    std::string cancel_reason;  // set with `cancel`, under the service's mutex
    std::vector<std::string> axes;
    bool keep_after_disconnect = false;
    std::string owner;                // who submitted it
    double accepted_unix_s = 0.0;
    double ended_unix_s = 0.0;
    std::size_t spec_bytes = 0;       // counted against max_queued_spec_bytes while it waits
    // Under the service's mutex: the iterations reported so far (until it ends), its end (once
    // it has ended; a job dropped from the queue has none) and who follows it.
    std::vector<netmc::v1::IterationMetrics> iterations;
    std::optional<netmc::v1::JobFinished> finished;
    std::vector<Watcher> watchers;
  };
  struct Submission {
    std::shared_ptr<management::Peer> session;
    netmc::v1::Request request;
  };

  // The validation thread: checks each submitted spec, then queues the job.
  void validate();
  void admit(const Submission& submission);
  // Under mutex_: cancels the jobs whose connection closed (unless kept) and forgets the oldest
  // ended jobs beyond the history.
  void tend_jobs();

  // Starts every queued job whose axes are free, in submission order: a job never overtakes an
  // earlier one that waits for one of its axes.
  void schedule();
  // Before the threads start: the store's unfinished jobs (a running one failed by the restart,
  // the queued ones queued again in their order) and its latest ended ones.
  void restore_from_store();
  void run(const std::shared_ptr<Job>& job);
  // Under mutex_: a queued job ends without running (cancelled, its client gone).
  void end_queued(Job& job, const std::string& reason);
  // What a running job waits for before its first cycle, for `netmc status` ("" none). Takes mutex_.
  void set_waiting_for(Job& job, const std::string& what);
  // The job has ended with `finished`: kept in the store, then its status, watchers and client.
  void conclude(const std::shared_ptr<Job>& job, netmc::v1::JobFinished finished);
  // netmc jobs: the history, from the store (or from memory without one).
  netmc::v1::JobList list_jobs(const netmc::v1::ListJobs& filter) const;
  void finish(const std::shared_ptr<Job>& job);
  void reply(Job& job, netmc::v1::Response response);
  // Under mutex_: a new watcher of `job` gets its status and the iterations so far (and its end,
  // if it has ended); refused with a reason if the job has too many watchers already.
  void start_watch(Job& job, const std::shared_ptr<management::Peer>& session, std::uint64_t request_id);
  // Under mutex_: `job` has ended with `finished`: each watcher gets it and is let go.
  void end_watches(Job& job, const netmc::v1::JobFinished& finished);

  // The nodes hosting the job's axes, checked against its clock and plant, matched by DDS.
  std::vector<NodeRecord> find_nodes(const Job& job, const JobChannels& channels);
  eprosima::fastdds::dds::DataWriter* setpoint_writer(bool realtime, const std::string& axis);
  struct AxisReaders {
    eprosima::fastdds::dds::DataReader* feedback = nullptr;  // the job's clock
    eprosima::fastdds::dds::DataReader* events = nullptr;
  };
  const AxisReaders& axis_readers(bool realtime, const std::string& axis);

  dds::DdsContext& context_;
  NodeDirectory& nodes_;
  ClockTracker& clocks_;
  JobServiceOptions options_;
  eprosima::fastdds::dds::DataWriter* control_;
  std::mutex endpoints_mutex_;  // the per-axis endpoints below
  std::map<std::pair<bool, std::string>, eprosima::fastdds::dds::DataWriter*> setpoint_writers_;
  std::map<std::pair<bool, std::string>, AxisReaders> axis_readers_;
  eprosima::fastdds::dds::DataWriter* iteration_logs_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  ServiceTotals totals_;  // under mutex_ (jobs_by_state filled by totals())
  std::deque<std::shared_ptr<Job>> queue_;
  std::map<std::uint64_t, std::shared_ptr<Job>> jobs_;
  std::set<std::string> busy_axes_;
  std::map<std::uint64_t, std::thread> running_;   // job threads, by job id
  std::vector<std::thread> finished_;              // to be joined
  std::deque<Submission> submissions_;            // waiting for validation
  std::size_t queued_spec_bytes_ = 0;              // of the submissions and the queue
  std::deque<std::uint64_t> ended_;                // ended job ids, oldest first
  std::uint64_t next_id_ = 1;
  bool stopping_ = false;
  std::thread scheduler_;
  std::thread validator_;
};

}  // namespace netmc::service
