#include "server/axis/setpoint_intake.hpp"

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

namespace netmc::axis {

void SetpointIntake::on_data_available(eprosima::fastdds::dds::DataReader* reader) {
  netmc::dds::Setpoint sample;
  eprosima::fastdds::dds::SampleInfo info;
  while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    if (!accept_(info.sample_identity.writer_guid().guidPrefix, sample)) {
      ++dropped_;
      continue;
    }
    std::lock_guard lock(mutex_);
    if (queue_.size() >= kMaxQueued) {
      queue_.pop_front();
      ++overflowed_;
    }
    queue_.push_back(std::move(sample));
    arrived_.set_trigger_value(true);
  }
}

std::optional<netmc::dds::Setpoint> SetpointIntake::take() {
  std::lock_guard lock(mutex_);
  if (queue_.empty()) {
    arrived_.set_trigger_value(false);
    return std::nullopt;
  }
  netmc::dds::Setpoint setpoint = std::move(queue_.front());
  queue_.pop_front();
  return setpoint;
}

}  // namespace netmc::axis
