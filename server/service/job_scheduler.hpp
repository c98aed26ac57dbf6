#pragma once
// Which job of netmc-server runs when: the validation thread checks each submitted spec and
// queues the job; the scheduler thread starts every queued job whose axes are free (a thread per
// job, run by the executor), joins ended job threads and drops jobs of closed connections.
// See docs/architecture.md, Threads and queues.

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "idl/management.pb.h"
#include "server/management/management_server.hpp"
#include "server/service/job_executor.hpp"
#include "server/service/job_registry.hpp"
#include "server/service/job_service_options.hpp"

namespace netmc::service {

class JobScheduler {
 public:
  // Queues the store's unfinished jobs again (with a store), then starts both threads.
  JobScheduler(JobRegistry& registry, JobExecutor& executor, const JobServiceOptions& options);
  // Cancels every job and waits for every thread.
  ~JobScheduler();
  JobScheduler(const JobScheduler&) = delete;
  JobScheduler& operator=(const JobScheduler&) = delete;

  // Takes the registry's lock: the submission waits for validation, or the reason it is refused
  // (queue full).
  std::optional<std::string> submit(const std::shared_ptr<management::Peer>& session,
                                    const netmc::v1::Request& request);
  // Under the registry's lock, `job` cancelled: a queued job leaves the queue now, not when the
  // job ahead of it ends. True if it was queued.
  bool drop_if_queued(const std::shared_ptr<Job>& job);
  // Cancels every job and waits for every thread (idempotent).
  void stop();

 private:
  struct Submission {
    std::shared_ptr<management::Peer> session;
    netmc::v1::Request request;
  };

  // The validation thread: checks each submitted spec, then queues the job.
  void validate();
  void admit(const Submission& submission);
  // The scheduler thread: starts every queued job whose axes are free, in submission order: a
  // job never overtakes an earlier one that waits for one of its axes.
  void schedule();
  // Under the registry's lock: cancels the jobs whose connection closed (unless kept) and
  // forgets the oldest ended jobs beyond the history.
  void tend_jobs();
  // Under the registry's lock: a queued job ends without running.
  void end_queued(const std::shared_ptr<Job>& job, const std::string& reason);
  // On the job's thread, after it ran: frees its axes and hands its thread to be joined.
  void finish(const std::shared_ptr<Job>& job);

  JobRegistry& registry_;
  JobExecutor& executor_;
  const JobServiceOptions& options_;
  // All below under registry_.mutex(); wake_ signals both threads (submissions, ends, stop).
  std::condition_variable wake_;
  std::deque<Submission> submissions_;             // waiting for validation
  std::deque<std::shared_ptr<Job>> queue_;         // validated, waiting for their axes
  std::size_t queued_spec_bytes_ = 0;              // of the submissions and the queue
  std::set<std::string> busy_axes_;
  std::map<std::uint64_t, std::thread> running_;   // job threads, by job id
  std::vector<std::thread> finished_;              // to be joined
  bool stopping_ = false;
  std::thread scheduler_;
  std::thread validator_;
};

}  // namespace netmc::service
