#pragma once
// netmc-server's job service: accepts jobs over the management endpoint, runs them on the
// discovered axis nodes over DDS, streams each iteration's metrics back to the submitting client
// and keeps every job's status. Jobs on disjoint axes run at once, each on a thread of its own
// with DDS readers of its own (in its axes' partitions, so no job sees another's samples); a
// job waits in the queue only while one of its axes is busy, or the running-job limit is reached.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "idl/management.pb.h"
#include "server/dds/dds_context.hpp"
#include "server/management/management_server.hpp"
#include "server/service/clock_tracker.hpp"
#include "server/service/job_executor.hpp"
#include "server/service/job_registry.hpp"
#include "server/service/job_scheduler.hpp"
#include "server/service/job_service_options.hpp"
#include "server/service/node_directory.hpp"

namespace netmc::service {

// The façade: answers each management request, with the jobs held by the registry, queued and
// started by the scheduler and run by the executor. See docs/architecture.md, Threads and queues.
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
  // otherwise only the connection that submitted a job, or one showing the job's cancel token.
  void handle(const std::shared_ptr<management::Peer>& session, const netmc::v1::Request& request,
              bool admin = false);

  ServiceTotals totals() const;

 private:
  // netmc nodes's view of one node (also the answer to a reset).
  void fill_node_info(const NodeRecord& record, std::chrono::steady_clock::time_point now,
                      netmc::v1::NodeInfo& info) const;
  std::optional<NodeRecord> find_node(const std::string& name) const;
  // An operator's commissioning command (netmc enable, disable, quick-stop, move, jog): checked,
  // numbered and sent to the node; the reply carries its number, which the node's status echoes.
  void command_axis(const std::shared_ptr<management::Peer>& session, const netmc::v1::Request& request, bool admin);

  dds::DdsContext& context_;
  NodeDirectory& nodes_;
  ClockTracker& clocks_;
  JobServiceOptions options_;  // the parts below keep a reference to it
  JobRegistry registry_;
  JobExecutor executor_;
  JobScheduler scheduler_;  // last: its threads use the parts above, and it stops first
  // Commissioning command numbers: from the clock, so that a restarted server does not repeat
  // the numbers a node echoes from before.
  std::atomic<std::uint64_t> next_command_number_;
};

}  // namespace netmc::service
