#pragma once
// A node's setpoints, filtered where they arrive. Fast DDS keeps one history per reader, keyed
// by axis and shared by every writer: a stranger's setpoints, taken by the node's loop only after
// they were stored, pushed the job's server's own out of that history (keep-last) and kept the
// loop busy dropping them while the job's control waited. Here each sample is taken on Fast DDS's
// receive thread as it arrives; only those `accept` keeps (the participant that holds the axis,
// for its job) reach the node's loop, through a bounded queue; the others are counted and gone.
// See docs/architecture.md, "Threads and queues".

#include <fastdds/dds/core/condition/GuardCondition.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/rtps/common/GuidPrefix_t.hpp>

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>

#include "dds_types.h"

namespace netmc::axis {

class SetpointIntake : public eprosima::fastdds::dds::DataReaderListener {
 public:
  // Decides on the receive thread, from the sending participant and the sample.
  using Accept = std::function<bool(const eprosima::fastrtps::rtps::GuidPrefix_t& sender,
                                    const netmc::dds::Setpoint& setpoint)>;
  // Accepted setpoints waiting for the loop: a 10 kHz job's 400 ms (the oldest go first beyond).
  static constexpr std::size_t kMaxQueued = 4096;

  explicit SetpointIntake(Accept accept) : accept_(std::move(accept)) {}
  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;

  // The oldest accepted setpoint; none resets arrived().
  std::optional<netmc::dds::Setpoint> take();
  // Triggered while accepted setpoints wait: for the loop's WaitSet.
  eprosima::fastdds::dds::GuardCondition& arrived() { return arrived_; }
  std::uint64_t dropped() const { return dropped_.load(); }
  std::uint64_t overflowed() const { return overflowed_.load(); }

 private:
  Accept accept_;
  std::mutex mutex_;
  std::deque<netmc::dds::Setpoint> queue_;
  eprosima::fastdds::dds::GuardCondition arrived_;
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> overflowed_{0};
};

}  // namespace netmc::axis
