#include "server/dds/dds_context.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <thread>

#include "server/dds/dds_locators.hpp"
#include "server/dds/discovery_server_watch.hpp"
#include "server/dds/dds_security_settings.hpp"

namespace netmc::dds {

using namespace eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;

std::string prefix_text(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  std::string out;
  char byte[3];
  for (const auto value : prefix.value) {
    std::snprintf(byte, sizeof byte, "%02x", static_cast<unsigned>(value));
    out += byte;
  }
  return out;
}

bool sent_by(const eprosima::fastrtps::rtps::GuidPrefix_t& sender, const std::string& identity) {
  constexpr char kDigits[] = "0123456789abcdef";
  if (identity.size() != 2 * sender.size) return false;
  for (std::size_t i = 0; i < sender.size; ++i) {
    if (identity[2 * i] != kDigits[sender.value[i] >> 4] || identity[2 * i + 1] != kDigits[sender.value[i] & 0xf]) {
      return false;
    }
  }
  return true;
}

// Keeps the participants of the endpoints a writer or reader is matched with (2.9 has no
// get_matched_subscriptions).
class DdsContext::MatchTracker : public DataWriterListener, public DataReaderListener {
 public:
  explicit MatchTracker(DataReaderListener* on_data = nullptr) : on_data_(on_data) {}
  void on_data_available(DataReader* reader) override {
    if (on_data_) on_data_->on_data_available(reader);
  }
  void on_publication_matched(DataWriter*, const PublicationMatchedStatus& status) override {
    count(status.last_subscription_handle, status.current_count_change);
  }
  void on_subscription_matched(DataReader*, const SubscriptionMatchedStatus& status) override {
    count(status.last_publication_handle, status.current_count_change);
  }

  bool has(const std::vector<std::string>& participants) const {
    std::lock_guard lock(mutex_);
    return std::all_of(participants.begin(), participants.end(),
                       [&](const std::string& p) { return endpoints_.count(p) > 0; });
  }

 private:
  void count(const InstanceHandle_t& handle, int change) {
    const std::string participant = prefix_text(eprosima::fastrtps::rtps::iHandle2GUID(handle).guidPrefix);
    std::lock_guard lock(mutex_);
    if (change > 0) {
      ++endpoints_[participant];
    } else if (change < 0) {
      const auto it = endpoints_.find(participant);
      if (it != endpoints_.end() && --it->second <= 0) endpoints_.erase(it);
    }
  }

  DataReaderListener* on_data_;
  mutable std::mutex mutex_;
  std::map<std::string, int> endpoints_;
};

// The participants of the domain as discovery announced them: the name each gave itself and,
// under DDS Security, the subject of the certificate its identity token names (the name is the
// participant's own word; the certificate is what authentication checked against the lab's CA).
class DdsContext::ParticipantDirectory : public DomainParticipantListener {
 public:
  void on_participant_discovery(DomainParticipant*, eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override {
    using Status = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo::DISCOVERY_STATUS;
    if (info.status == Status::DISCOVERED_PARTICIPANT && discovery_servers_) {
      discovery_servers_->discovered(info.info.m_guid.guidPrefix);
    }
    const std::string key = prefix_text(info.info.m_guid.guidPrefix);
    std::lock_guard lock(mutex_);
    if (info.status == Status::REMOVED_PARTICIPANT || info.status == Status::DROPPED_PARTICIPANT) {
      known_.erase(key);
      return;
    }
    if (known_.size() >= static_cast<std::size_t>(kMaxInstances) && !known_.count(key)) return;
    ParticipantIdentity identity;
    identity.name = std::string(info.info.m_participantName.c_str()).substr(0, 255);
#if HAVE_SECURITY
    for (const auto& property : info.info.identity_token_.properties()) {
      if (property.name() == "dds.cert.sn") identity.certificate_subject = property.value().substr(0, 255);
    }
#endif
    known_[key] = std::move(identity);
  }

  // Before the participant exists: its listener then never sees the watch change.
  void watch_discovery_servers(const DdsOptions& options) {
    discovery_servers_ = std::make_unique<DiscoveryServerWatch>(options.discovery_servers, options.interfaces);
  }

  std::optional<ParticipantIdentity> find(const std::string& prefix) const {
    std::lock_guard lock(mutex_);
    const auto it = known_.find(prefix);
    if (it == known_.end()) return std::nullopt;
    return it->second;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, ParticipantIdentity> known_;
  std::unique_ptr<DiscoveryServerWatch> discovery_servers_;
};

std::optional<ParticipantIdentity> DdsContext::participant_identity(
    const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) const {
  return participants_->find(prefix_text(prefix));
}

DdsContext::DdsContext(const DdsOptions& options) : participants_(std::make_unique<ParticipantDirectory>()) {
  auto* factory = DomainParticipantFactory::get_instance();
  if (!options.xml_profile_file.empty() && !std::filesystem::is_regular_file(options.xml_profile_file)) {
    throw std::invalid_argument("--dds-profile: no such file '" + options.xml_profile_file + "'");
  }
  if (!options.xml_profile_file.empty() &&
      factory->load_XML_profiles_file(options.xml_profile_file) != ReturnCode_t::RETCODE_OK) {
    throw std::invalid_argument("--dds-profile: cannot load Fast DDS XML profiles from '" +
                                options.xml_profile_file + "'");
  }
  // Fast DDS loads FASTRTPS_DEFAULT_PROFILES_FILE by itself; its topic profiles apply too.
  const char* env_profiles = std::getenv("FASTRTPS_DEFAULT_PROFILES_FILE");
  xml_loaded_ = !options.xml_profile_file.empty() || (env_profiles && *env_profiles);
  if (!options.participant_profile.empty()) {
    // The profile's QoS under netmc's own participant name (--dds-name, a node's --node): the name
    // is what nodes obey (--server-name) and what the server lists nodes by, whatever a profile says.
    DomainParticipantQos qos;
    if (factory->get_participant_qos_from_profile(options.participant_profile, qos) != ReturnCode_t::RETCODE_OK) {
      throw std::invalid_argument("--dds-participant-profile: no participant profile '" +
                                  options.participant_profile.substr(0, 128) + "' in the loaded XML profiles");
    }
    qos.name(options.name);
    participant_ = factory->create_participant(options.domain_id, qos, participants_.get(), StatusMask::none());
    transport_description_ = "XML profile " + options.participant_profile;
  } else {
    // The XML default participant profile, if any, is the starting point (Fast DDS reads the
    // profiles files only when asked, or inside create_participant).
    factory->load_profiles();
    DomainParticipantQos qos = factory->get_default_participant_qos();
    qos.name(options.name);
    auto& builtin = qos.wire_protocol().builtin;
    // A participant that dies without saying goodbye is forgotten after 10 s (Fast DDS: 20 s);
    // announcements every second keep a lossy link from expiring a live one.
    builtin.discovery_config.leaseDuration = Duration_t(10, 0);
    builtin.discovery_config.leaseDuration_announcementperiod = Duration_t(1, 0);

    transport_description_ = configure_transport(qos, options);
    if (!options.security_dir.empty()) {
      add_security_properties(qos, options.security_dir, options.name);
      transport_description_ += ", DDS Security as " + options.name;
    }
    if (!options.discovery_servers.empty()) participants_->watch_discovery_servers(options);
    // The listener sees discovery only (StatusMask::none: no entity's data falls back to it).
    participant_ = factory->create_participant(options.domain_id, qos, participants_.get(), StatusMask::none());
  }
  if (!participant_) {
    throw std::runtime_error("dds: cannot create a participant in domain " + std::to_string(options.domain_id) +
                             (options.security_dir.empty()
                                  ? std::string()
                                  : " (with DDS Security from " + options.security_dir +
                                        ": is the certificate of '" + options.name +
                                        "' signed by its ca.pem, and are the governance and permissions signed by it?)"));
  }
  identity_ = prefix_text(participant_->guid().guidPrefix);
  publisher_ = participant_->create_publisher(PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  if (!publisher_ || !subscriber_) throw std::runtime_error("dds: cannot create publisher/subscriber");
}

DdsContext::~DdsContext() {
  if (participant_) {
    participant_->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
}

Publisher* DdsContext::publisher_for(const std::string& partition) {
  // Called with entities_mutex_ held.
  if (partition.empty()) return publisher_;
  auto& publisher = partition_publishers_[partition];
  if (!publisher) {
    PublisherQos qos = PUBLISHER_QOS_DEFAULT;
    qos.partition().push_back(partition.c_str());
    publisher = participant_->create_publisher(qos);
    if (!publisher) throw std::runtime_error("dds: cannot create a publisher for partition " + partition);
  }
  return publisher;
}

DataWriter* DdsContext::writer(Topic* topic, Delivery delivery, const std::string& partition) {
  std::lock_guard lock(entities_mutex_);
  Publisher* publisher = publisher_for(partition);
  DataWriterQos qos = DATAWRITER_QOS_DEFAULT;
  // An XML <data_writer profile_name="TOPIC"> replaces the built-in QoS of that topic.
  if (!xml_loaded_ ||
      publisher->get_datawriter_qos_from_profile(topic->get_name(), qos) != ReturnCode_t::RETCODE_OK) {
    qos = DATAWRITER_QOS_DEFAULT;
    apply_delivery_qos(qos, delivery);
  }
  auto tracker = std::make_unique<MatchTracker>();
  auto* created = publisher->create_datawriter(topic, qos, tracker.get(),
                                                StatusMask::publication_matched());
  if (!created) throw std::runtime_error("dds: cannot create a writer for " + topic->get_name());
  trackers_[created] = std::move(tracker);
  return created;
}

DataReader* DdsContext::reader(Topic* topic, Delivery delivery, const std::vector<std::string>& partitions,
                               DataReaderListener* on_data) {
  std::lock_guard lock(entities_mutex_);
  Subscriber* subscriber = subscriber_;
  if (!partitions.empty()) {
    SubscriberQos subscriber_qos = SUBSCRIBER_QOS_DEFAULT;
    for (const auto& partition : partitions) subscriber_qos.partition().push_back(partition.c_str());
    subscriber = participant_->create_subscriber(subscriber_qos);
    if (!subscriber) throw std::runtime_error("dds: cannot create a subscriber for " + topic->get_name());
  }
  DataReaderQos qos = DATAREADER_QOS_DEFAULT;
  // An XML <data_reader profile_name="TOPIC"> replaces the built-in QoS of that topic.
  if (!xml_loaded_ ||
      subscriber->get_datareader_qos_from_profile(topic->get_name(), qos) != ReturnCode_t::RETCODE_OK) {
    qos = DATAREADER_QOS_DEFAULT;
    apply_delivery_qos(qos, delivery);
  }
  auto tracker = std::make_unique<MatchTracker>(on_data);
  StatusMask mask = StatusMask::subscription_matched();
  if (on_data) mask << StatusMask::data_available();
  auto* created = subscriber->create_datareader(topic, qos, tracker.get(), mask);
  if (!created) throw std::runtime_error("dds: cannot create a reader for " + topic->get_name());
  trackers_[created] = std::move(tracker);
  return created;
}

void DdsContext::remove_reader(DataReader* reader) {
  std::lock_guard lock(entities_mutex_);
  const_cast<Subscriber*>(reader->get_subscriber())->delete_datareader(reader);
  trackers_.erase(reader);
}

bool DdsContext::matches_participants(const DomainEntity* endpoint,
                                      const std::vector<std::string>& participants) const {
  std::lock_guard lock(entities_mutex_);
  const auto it = trackers_.find(endpoint);
  return it != trackers_.end() && it->second->has(participants);
}

bool DdsContext::wait_for_participants(const DomainEntity* endpoint, const std::vector<std::string>& participants,
                                       std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!matches_participants(endpoint, participants)) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

void write_checked(DataWriter* writer, void* sample) {
  if (!writer->write(sample)) {
    throw std::runtime_error("dds: a write on " + writer->get_topic()->get_name() +
                             " was refused (out of resources or not enabled)");
  }
}

namespace {

// Polls `matched()` (the endpoints an endpoint has matched) until it reaches `count`.
template <typename Matched>
bool wait_until_matched(const Matched& matched, int count, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (matched() >= count) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

}  // namespace

bool wait_for_readers(DataWriter* writer, int count, std::chrono::milliseconds timeout) {
  return wait_until_matched(
      [writer] {
        PublicationMatchedStatus status;
        writer->get_publication_matched_status(status);
        return status.current_count;
      },
      count, timeout);
}

bool wait_for_writers(DataReader* reader, int count, std::chrono::milliseconds timeout) {
  return wait_until_matched(
      [reader] {
        SubscriptionMatchedStatus status;
        reader->get_subscription_matched_status(status);
        return status.current_count;
      },
      count, timeout);
}

std::chrono::system_clock::time_point received_at(const SampleInfo& info) {
  const auto& stamp = info.reception_timestamp;
  if (stamp.seconds() <= 0) return std::chrono::system_clock::now();
  return std::chrono::system_clock::time_point(std::chrono::duration_cast<std::chrono::system_clock::duration>(
      std::chrono::seconds(stamp.seconds()) + std::chrono::nanoseconds(stamp.nanosec())));
}

}  // namespace netmc::dds
