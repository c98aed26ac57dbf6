#pragma once
// Measures every live node's clock against the server's by two-way time transfer over DDS
// (ClockProbe / ClockReply): a probe to each node every kProbePeriod, the best of the newest
// kProbeWindow exchanges by round trip (netsim::ClockOffsetEstimator). It runs before and
// during jobs alike, so a realtime job starts on a fresh estimate and every iteration re-maps
// its start onto each node's clock.

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "dds_types.h"
#include "netsim/clock_offset_estimator.hpp"
#include "server/dds/dds_context.hpp"
#include "server/dds/time_base.hpp"
#include "server/service/node_directory.hpp"

namespace netmc::service {

// Every node receives every probe (and drops the others'): 5 a second per node keeps that cheap.
inline constexpr std::chrono::milliseconds kProbePeriod{200};
inline constexpr std::size_t kProbeWindow = 16;

class ClockTracker {
 public:
  ClockTracker(dds::DdsContext& context, const NodeDirectory& nodes, dds::TimeBase base);
  ~ClockTracker();
  ClockTracker(const ClockTracker&) = delete;
  ClockTracker& operator=(const ClockTracker&) = delete;

  // The node's clock minus the server's, if at least `min_exchanges` probes came back.
  std::optional<netsim::ClockOffsetEstimate> estimate(const std::string& node,
                                                      std::size_t min_exchanges = 1) const;
  double now_s() const { return dds::time_base_now_s(base_); }
  dds::TimeBase time_base() const { return base_; }

 private:
  void run();

  struct Tracked {
    std::string participant;
    netsim::ClockOffsetEstimator estimator{kProbeWindow};
  };

  const NodeDirectory& nodes_;
  dds::TimeBase base_;
  std::string server_;
  eprosima::fastdds::dds::DataWriter* probes_;
  dds::SampleReader<netmc::dds::ClockReply> replies_;
  mutable std::mutex mutex_;
  std::map<std::string, Tracked> tracked_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace netmc::service
