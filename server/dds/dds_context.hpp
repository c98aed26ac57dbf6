#pragma once
// One DDS domain participant with the netmc topics, and typed writers/readers with the QoS of
// each kind of data. Control data (setpoints, feedback) is reliable with keep-last 64 per axis
// in both clock modes: lockstep needs every sample (the network is emulated by netsim, so the
// transport must not lose any), and in realtime the iteration start/stop messages travel on the
// same topic; a writer with keep-last never blocks, and stale commands are dropped at the axis
// by sequence number.

#include <fastdds/dds/core/condition/WaitSet.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace netmc::dds {

enum class Transport {
  builtin,   // Fast DDS defaults: shared memory on one host (invisible to network emulation), UDP
  udp,       // UDPv4 only: what real hosts use and what netem/namespaces see
};

struct DdsOptions {
  int domain_id = 0;
  Transport transport = Transport::builtin;
  std::string xml_profile_file;     // optional Fast DDS XML profiles, loaded first
  std::string participant_profile;  // optional participant profile name in that file
  std::string name = "netmc";
};

enum class Delivery {
  control,            // reliable, keep-last 64 per key, volatile
  log,                // reliable, transient-local, keep-last 64
  status,             // reliable, transient-local, keep-last 1 (per key), automatic liveliness
};

class DdsContext {
 public:
  explicit DdsContext(const DdsOptions& options);
  ~DdsContext();
  DdsContext(const DdsContext&) = delete;
  DdsContext& operator=(const DdsContext&) = delete;

  // Registers `PubSubType` once and creates (or reuses) the topic.
  template <typename PubSubType>
  eprosima::fastdds::dds::Topic* topic(const std::string& name);

  eprosima::fastdds::dds::DataWriter* writer(eprosima::fastdds::dds::Topic* topic, Delivery delivery);
  eprosima::fastdds::dds::DataReader* reader(eprosima::fastdds::dds::Topic* topic, Delivery delivery);

  std::string describe_transport() const { return transport_description_; }

 private:
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
  std::string transport_description_;
  bool xml_loaded_ = false;
};

template <typename PubSubType>
eprosima::fastdds::dds::Topic* DdsContext::topic(const std::string& name) {
  if (const auto it = topics_.find(name); it != topics_.end()) return it->second;
  eprosima::fastdds::dds::TypeSupport type(new PubSubType());
  type.register_type(participant_);
  auto* created =
      participant_->create_topic(name, type.get_type_name(), eprosima::fastdds::dds::TOPIC_QOS_DEFAULT);
  if (!created) throw std::runtime_error("dds: cannot create topic " + name);
  topics_[name] = created;
  return created;
}

// Blocking take of one valid sample with a timeout, for the lockstep loops.
template <typename Sample>
class SampleReader {
 public:
  explicit SampleReader(eprosima::fastdds::dds::DataReader* reader) : reader_(reader) {
    auto& condition = reader_->get_statuscondition();
    condition.set_enabled_statuses(eprosima::fastdds::dds::StatusMask::data_available());
    waitset_.attach_condition(condition);
  }

  std::optional<Sample> take(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    Sample sample;
    eprosima::fastdds::dds::SampleInfo info;
    while (true) {
      while (reader_->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
        if (info.valid_data) return sample;
      }
      const auto left = deadline - std::chrono::steady_clock::now();
      if (left <= std::chrono::milliseconds(0)) return std::nullopt;
      const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(left).count();
      eprosima::fastdds::dds::ConditionSeq active;
      waitset_.wait(active, eprosima::fastrtps::Duration_t(static_cast<int32_t>(ns / 1000000000),
                                                          static_cast<uint32_t>(ns % 1000000000)));
    }
  }

  eprosima::fastdds::dds::DataReader* get() const { return reader_; }

 private:
  eprosima::fastdds::dds::DataReader* reader_;
  eprosima::fastdds::dds::WaitSet waitset_;
};

// Waits until `writer` has matched at least `count` readers (discovery), up to `timeout`.
bool wait_for_readers(eprosima::fastdds::dds::DataWriter* writer, int count,
                      std::chrono::milliseconds timeout);

}  // namespace netmc::dds
