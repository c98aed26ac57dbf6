#pragma once
// netmc-server's job service: accepts jobs over the management endpoint, runs them one at a time
// on the discovered axis nodes (lockstep over DDS), streams each iteration's metrics back to the
// submitting client and keeps every job's status.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "idl/management.pb.h"
#include "server/dds/dds_context.hpp"
#include "server/management/management_server.hpp"
#include "server/service/clock_tracker.hpp"
#include "server/service/node_directory.hpp"

namespace netmc::service {

struct JobServiceOptions {
  std::chrono::milliseconds axis_timeout{2000};       // per lockstep exchange
  std::chrono::milliseconds discovery_timeout{10000}; // waiting for the nodes of a job
  std::chrono::milliseconds silence_limit{500};       // realtime: an axis silent this long fails
  dds::TimeBase time_base = dds::TimeBase::monotonic; // realtime jobs' schedule
};

class JobService {
 public:
  JobService(dds::DdsContext& context, NodeDirectory& nodes, ClockTracker& clocks,
             JobServiceOptions options);
  ~JobService();
  JobService(const JobService&) = delete;
  JobService& operator=(const JobService&) = delete;

  // Called on the management endpoint's thread for every request.
  void handle(const std::shared_ptr<management::Session>& session, const netmc::v1::Request& request);

 private:
  struct Job {
    std::uint64_t id = 0;
    netmc::v1::JobSpec spec;
    std::weak_ptr<management::Session> session;
    std::uint64_t request_id = 0;
    netmc::v1::JobStatus status;
    std::atomic<bool> cancel{false};
  };

  void work();
  void run(Job& job);
  void reply(Job& job, netmc::v1::Response response);

  // The nodes hosting the job's axes, checked against its clock and plant, matched by DDS.
  std::vector<NodeRecord> find_nodes(const Job& job);
  eprosima::fastdds::dds::DataWriter* setpoint_writer(bool realtime, const std::string& axis);

  dds::DdsContext& context_;
  NodeDirectory& nodes_;
  ClockTracker& clocks_;
  JobServiceOptions options_;
  eprosima::fastdds::dds::DataWriter* control_;
  std::map<std::pair<bool, std::string>, eprosima::fastdds::dds::DataWriter*> setpoint_writers_;  // worker thread
  dds::SampleReader<netmc::dds::Feedback> realtime_feedback_;
  dds::SampleReader<netmc::dds::Feedback> lockstep_feedback_;
  dds::SampleReader<netmc::dds::AxisEvent> events_;
  eprosima::fastdds::dds::DataWriter* iteration_logs_;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<Job>> queue_;
  std::map<std::uint64_t, std::shared_ptr<Job>> jobs_;
  std::uint64_t next_id_ = 1;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace netmc::service
