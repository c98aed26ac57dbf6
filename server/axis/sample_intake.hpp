#pragma once
// A node's setpoints and job controls, filtered where they arrive. Fast DDS keeps one history per
// reader, keyed by axis and shared by every writer: a stranger's samples, taken by the node's
// loop only after they were stored, pushed the server's own out of that history (keep-last) and
// kept the loop busy dropping them while the job waited (a flood of forged job controls could
// push out the real BEGIN_ITERATION). Here each sample is taken on Fast DDS's receive thread as
// it arrives; only those `accept` keeps reach the node's loop, through a bounded queue; the
// others are counted and gone.
// See docs/architecture.md, "Threads and queues".

#include <fastdds/dds/core/condition/GuardCondition.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/rtps/common/GuidPrefix_t.hpp>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <utility>

namespace netmc::axis {

template <typename Sample>
class SampleIntake : public eprosima::fastdds::dds::DataReaderListener {
 public:
  // Decides on the receive thread, from the sending participant and the sample.
  using Accept = std::function<bool(const eprosima::fastrtps::rtps::GuidPrefix_t& sender, const Sample& sample)>;

  // Beyond `max_queued` accepted samples waiting for the loop, the oldest go first.
  SampleIntake(Accept accept, std::size_t max_queued) : accept_(std::move(accept)), max_queued_(max_queued) {}

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
    Sample sample;
    eprosima::fastdds::dds::SampleInfo info;
    while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      if (!accept_(info.sample_identity.writer_guid().guidPrefix, sample)) {
        ++dropped_;
        continue;
      }
      std::lock_guard lock(mutex_);
      if (queue_.size() >= max_queued_) {
        queue_.pop_front();
        ++overflowed_;
      }
      queue_.push_back({info.sample_identity.writer_guid().guidPrefix, std::move(sample)});
      arrived_.set_trigger_value(true);
    }
  }

  // The oldest accepted sample; none resets arrived(). For the loop's thread only.
  std::optional<Sample> take() {
    std::lock_guard lock(mutex_);
    if (queue_.empty()) {
      arrived_.set_trigger_value(false);
      return std::nullopt;
    }
    Received received = std::move(queue_.front());
    queue_.pop_front();
    last_sender_ = received.sender;
    return std::move(received.sample);
  }
  // The participant that sent the sample take() returned last.
  const eprosima::fastrtps::rtps::GuidPrefix_t& last_sender() const { return last_sender_; }

  // Triggered while accepted samples wait: for the loop's WaitSet.
  eprosima::fastdds::dds::GuardCondition& arrived() { return arrived_; }
  std::uint64_t dropped() const { return dropped_.load(); }
  std::uint64_t overflowed() const { return overflowed_.load(); }

 private:
  Accept accept_;
  const std::size_t max_queued_;
  std::mutex mutex_;
  struct Received {
    eprosima::fastrtps::rtps::GuidPrefix_t sender;
    Sample sample;
  };
  std::deque<Received> queue_;
  eprosima::fastrtps::rtps::GuidPrefix_t last_sender_;
  eprosima::fastdds::dds::GuardCondition arrived_;
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> overflowed_{0};
};

}  // namespace netmc::axis
