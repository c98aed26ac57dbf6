#pragma once
// Runs one job of netmc-server on its own thread: finds and matches the axis nodes hosting its
// axes, gives it the DDS endpoints of those axes (made on first use and kept), runs the
// lockstep or realtime runner, and ends the job (the store, its status, watchers and client).
// See docs/architecture.md, Threads and queues.

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "server/dds/dds_context.hpp"
#include "server/service/clock_tracker.hpp"
#include "server/service/dds_job_messages.hpp"
#include "server/service/job_registry.hpp"
#include "server/service/job_service_options.hpp"
#include "server/service/node_directory.hpp"

namespace netmc::service {

class JobExecutor {
 public:
  JobExecutor(dds::DdsContext& context, NodeDirectory& nodes, ClockTracker& clocks, JobRegistry& registry,
              const JobServiceOptions& options);
  JobExecutor(const JobExecutor&) = delete;
  JobExecutor& operator=(const JobExecutor&) = delete;

  // On the job's thread: runs it to its end (done, failed or cancelled) and tells of the end.
  void run(const std::shared_ptr<Job>& job);

  // The job-control writer (job starts and ends, fault resets), made once.
  eprosima::fastdds::dds::DataWriter* control() const { return control_; }

 private:
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
  JobRegistry& registry_;
  const JobServiceOptions& options_;
  eprosima::fastdds::dds::DataWriter* control_;
  eprosima::fastdds::dds::DataWriter* iteration_logs_;
  // Guards the per-axis endpoints below (job threads make them at once); taken alone, never
  // with the registry's lock.
  std::mutex endpoints_mutex_;
  std::map<std::pair<bool, std::string>, eprosima::fastdds::dds::DataWriter*> setpoint_writers_;
  std::map<std::pair<bool, std::string>, AxisReaders> axis_readers_;
};

}  // namespace netmc::service
