#pragma once
// One DDS domain participant with the netmc topics, and typed writers/readers with the QoS of
// each kind of data (topics in server/dds/topics.hpp, their types in idl/dds_types.idl, their QoS
// in server/dds/dds_qos.hpp, where the participant talks in server/dds/dds_locators.hpp); see
// docs/architecture.md.

#include <fastdds/dds/core/condition/WaitSet.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/common/GuidPrefix_t.hpp>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "server/dds/dds_options.hpp"
#include "server/dds/dds_qos.hpp"

namespace netmc::dds {

// What a participant said of itself in discovery.
struct ParticipantIdentity {
  std::string name;                 // its participant name (netmc: --dds-name, a node's --node)
  std::string certificate_subject;  // DDS Security: its certificate's subject ("CN=..."); "" without
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

  // With a partition (writer) or partitions (reader), the endpoint matches only endpoints that
  // share one: DDS decides it once, at discovery, so a node is never sent another axis's
  // setpoints (partition_of_axis).
  eprosima::fastdds::dds::DataWriter* writer(eprosima::fastdds::dds::Topic* topic, Delivery delivery,
                                             const std::string& partition = "");
  // With `on_data`, the reader's samples are announced to it on Fast DDS's receive thread
  // (on_data_available), which must take them: a reader that filters there keeps what it drops
  // out of its history. `on_data` outlives the reader (remove_reader).
  eprosima::fastdds::dds::DataReader* reader(eprosima::fastdds::dds::Topic* topic, Delivery delivery,
                                             const std::vector<std::string>& partitions = {},
                                             eprosima::fastdds::dds::DataReaderListener* on_data = nullptr);

  // Deletes a reader made by reader() without partitions that is no longer needed (its samples,
  // its matches); partitioned readers are kept for the process's life (JobService).
  void remove_reader(eprosima::fastdds::dds::DataReader* reader);

  std::string describe_transport() const { return transport_description_; }
  // This participant's GUID prefix as 24 hex digits: the identity of a server or a node.
  std::string identity() const { return identity_; }
  // The participant `prefix` as discovery announced it; nullopt for one not (or no longer) known.
  std::optional<ParticipantIdentity> participant_identity(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) const;

  // True once `endpoint` (a writer or reader made by this context) has matched an endpoint of
  // every participant in `participants` (GUID prefixes as identity() prints them). A restarted
  // node has a new prefix, so an endpoint of its dead predecessor that DDS still counts does not
  // satisfy this.
  bool matches_participants(const eprosima::fastdds::dds::DomainEntity* endpoint,
                            const std::vector<std::string>& participants) const;
  bool wait_for_participants(const eprosima::fastdds::dds::DomainEntity* endpoint,
                             const std::vector<std::string>& participants,
                             std::chrono::milliseconds timeout) const;

 private:
  class MatchTracker;
  class ParticipantDirectory;
  std::unique_ptr<ParticipantDirectory> participants_;  // the participant's listener
  eprosima::fastdds::dds::Publisher* publisher_for(const std::string& partition);
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
  std::map<std::string, eprosima::fastdds::dds::Publisher*> partition_publishers_;
  std::string transport_description_;
  std::string identity_;
  bool xml_loaded_ = false;
  // Jobs run on threads of their own and make and remove their endpoints concurrently.
  mutable std::mutex entities_mutex_;
  std::map<const eprosima::fastdds::dds::DomainEntity*, std::unique_ptr<MatchTracker>> trackers_;
};

template <typename PubSubType>
eprosima::fastdds::dds::Topic* DdsContext::topic(const std::string& name) {
  std::lock_guard lock(entities_mutex_);
  if (const auto it = topics_.find(name); it != topics_.end()) return it->second;
  eprosima::fastdds::dds::TypeSupport type(new PubSubType());
  type.register_type(participant_);
  auto* created =
      participant_->create_topic(name, type.get_type_name(), eprosima::fastdds::dds::TOPIC_QOS_DEFAULT);
  if (!created) throw std::runtime_error("dds: cannot create topic " + name);
  topics_[name] = created;
  return created;
}

// The DDS partition of one axis's setpoints.
inline std::string partition_of_axis(const std::string& axis) { return "netmc.axis." + axis; }

// Writes one sample; throws std::runtime_error naming the topic if DDS refuses it (out of
// resources, not enabled, ...): no write's result is ignored.
void write_checked(eprosima::fastdds::dds::DataWriter* writer, void* sample);

// The reception timestamp of a sample as a system_clock time (now, if Fast DDS left it unset).
std::chrono::system_clock::time_point received_at(const eprosima::fastdds::dds::SampleInfo& info);

// Blocking take of one valid sample with a timeout, from one reader or several (a job reads
// each of its axes' own reader; one WaitSet wakes on any of them).
template <typename Sample>
class SampleReader {
 public:
  explicit SampleReader(eprosima::fastdds::dds::DataReader* reader)
      : SampleReader(std::vector<eprosima::fastdds::dds::DataReader*>{reader}) {}
  explicit SampleReader(std::vector<eprosima::fastdds::dds::DataReader*> readers) : readers_(std::move(readers)) {
    for (auto* reader : readers_) {
      auto& condition = reader->get_statuscondition();
      condition.set_enabled_statuses(eprosima::fastdds::dds::StatusMask::data_available());
      waitset_.attach_condition(condition);
    }
  }

  template <typename Rep, typename Period>
  std::optional<Sample> take(std::chrono::duration<Rep, Period> timeout) {
    return take_until(std::chrono::steady_clock::now() +
                      std::chrono::duration_cast<std::chrono::steady_clock::duration>(timeout));
  }

  // Waits to the microsecond: a realtime cycle's budget is a fraction of a millisecond.
  std::optional<Sample> take_until(std::chrono::steady_clock::time_point deadline) {
    if (auto received = take_until_received(deadline)) return std::move(received->first);
    return std::nullopt;
  }

  // As take_until, with the time Fast DDS received the sample (system clock): stamped on its
  // receive thread, before this thread wakes, so clock probes measure the network and not the
  // wake-up of whoever reads them.
  std::optional<std::pair<Sample, std::chrono::system_clock::time_point>> take_until_received(
      std::chrono::steady_clock::time_point deadline) {
    while (true) {
      if (auto received = try_take_received()) return received;
      const auto left = deadline - std::chrono::steady_clock::now();
      if (left <= std::chrono::steady_clock::duration::zero()) return std::nullopt;
      const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(left).count();
      eprosima::fastdds::dds::ConditionSeq active;
      waitset_.wait(active, eprosima::fastrtps::Duration_t(static_cast<int32_t>(ns / 1000000000),
                                                          static_cast<uint32_t>(ns % 1000000000)));
    }
  }

  std::optional<Sample> try_take() {
    if (auto received = try_take_received()) return std::move(received->first);
    return std::nullopt;
  }

  eprosima::fastdds::dds::DataReader* get() const { return readers_.front(); }
  const std::vector<eprosima::fastdds::dds::DataReader*>& readers() const { return readers_; }
  // For a WaitSet that waits on several readers at once.
  eprosima::fastdds::dds::StatusCondition& condition() { return readers_.front()->get_statuscondition(); }

  // The participant whose writer sent the sample taken last: what a sample says of its own
  // origin (a `server` or `participant` field) is believed only if this agrees (sent_by).
  const eprosima::fastrtps::rtps::GuidPrefix_t& last_sender() const { return last_sender_; }

 private:
  // Round robin over the readers, so that no axis's samples wait behind another's.
  std::optional<std::pair<Sample, std::chrono::system_clock::time_point>> try_take_received() {
    Sample sample;
    eprosima::fastdds::dds::SampleInfo info;
    for (std::size_t tried = 0; tried < readers_.size(); ++tried) {
      auto* reader = readers_[next_];
      next_ = (next_ + 1) % readers_.size();
      while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
        if (info.valid_data) {
          last_sender_ = info.sample_identity.writer_guid().guidPrefix;
          return std::make_pair(std::move(sample), received_at(info));
        }
      }
    }
    return std::nullopt;
  }

  std::vector<eprosima::fastdds::dds::DataReader*> readers_;
  std::size_t next_ = 0;
  eprosima::fastrtps::rtps::GuidPrefix_t last_sender_;
  eprosima::fastdds::dds::WaitSet waitset_;
};

// Waits until `writer` has matched at least `count` readers (discovery), up to `timeout`.
bool wait_for_readers(eprosima::fastdds::dds::DataWriter* writer, int count,
                      std::chrono::milliseconds timeout);
// Waits until `reader` has matched at least `count` writers (discovery), up to `timeout`.
bool wait_for_writers(eprosima::fastdds::dds::DataReader* reader, int count, std::chrono::milliseconds timeout);

// A GUID prefix as 24 hex digits.
std::string prefix_text(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix);

// True if `identity` (24 hex digits, as prefix_text writes them) names `sender`. Without
// allocating: it runs for every setpoint and feedback sample. Without DDS Security this stops
// a participant that claims another's identity in a sample's fields; one that forges its RTPS
// GUID itself is stopped only by authentication (--security).
bool sent_by(const eprosima::fastrtps::rtps::GuidPrefix_t& sender, const std::string& identity);

}  // namespace netmc::dds
