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
#include "server/service/node_directory.hpp"

namespace netmc::service {

struct JobServiceOptions {
  std::chrono::milliseconds axis_timeout{2000};       // per lockstep exchange
  std::chrono::milliseconds discovery_timeout{10000}; // waiting for the nodes of a job
  std::uint32_t missed_cycles_limit = 20;             // realtime: periods without feedback
};

class JobService {
 public:
  JobService(dds::DdsContext& context, NodeDirectory& nodes, JobServiceOptions options);
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

  dds::DdsContext& context_;
  NodeDirectory& nodes_;
  JobServiceOptions options_;
  eprosima::fastdds::dds::DataWriter* setpoints_;
  dds::SampleReader<netmc::dds::Feedback> feedback_;
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
