#include "server/dds/dds_context.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/common/InstanceHandle.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>

namespace netmc::dds {
namespace {

using namespace eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

// Repair of a lost reliable sample: the writer announces what it has every 2 ms (Fast DDS's
// default is 3 s), answers a NACK at once, and the reader NACKs without delay. One lost
// sample of a lockstep exchange then costs about one heartbeat period.
template <typename Qos>
void fast_repair(Qos& qos);

template <>
void fast_repair(DataWriterQos& qos) {
  auto& times = qos.reliable_writer_qos().times;
  times.heartbeatPeriod = Duration_t(0, 2'000'000);
  times.initialHeartbeatDelay = Duration_t(0, 1'000'000);
  times.nackResponseDelay = Duration_t(0, 0);
  times.nackSupressionDuration = Duration_t(0, 0);
}

template <>
void fast_repair(DataReaderQos& qos) {
  auto& times = qos.reliable_reader_qos().times;
  times.heartbeatResponseDelay = Duration_t(0, 0);
  times.initialAcknackDelay = Duration_t(0, 1'000'000);
}

template <typename Qos>
void apply(Qos& qos, Delivery delivery) {
  qos.endpoint().history_memory_policy =
      eprosima::fastrtps::rtps::DYNAMIC_REUSABLE_MEMORY_MODE;
  qos.durability().kind = VOLATILE_DURABILITY_QOS;
  qos.history().kind = KEEP_LAST_HISTORY_QOS;
  int depth = 64;
  switch (delivery) {
    case Delivery::stream:
      qos.reliability().kind = BEST_EFFORT_RELIABILITY_QOS;
      depth = 8;
      break;
    case Delivery::exchange:
    case Delivery::control:
      // Keep-last rather than keep-all: a writer never blocks, and lockstep has at most one
      // sample per axis in flight.
      qos.reliability().kind = RELIABLE_RELIABILITY_QOS;
      fast_repair(qos);
      break;
    case Delivery::log:
      qos.reliability().kind = RELIABLE_RELIABILITY_QOS;
      qos.durability().kind = TRANSIENT_LOCAL_DURABILITY_QOS;
      break;
    case Delivery::status:
      qos.reliability().kind = RELIABLE_RELIABILITY_QOS;
      qos.durability().kind = TRANSIENT_LOCAL_DURABILITY_QOS;
      qos.liveliness().kind = AUTOMATIC_LIVELINESS_QOS;
      fast_repair(qos);
      depth = 1;
      break;
  }
  qos.history().depth = depth;
  // Fast DDS's default is 10 instances per endpoint: 10 nodes, 10 jobs' logs.
  qos.resource_limits().max_instances = kMaxInstances;
  qos.resource_limits().max_samples_per_instance = depth;
  qos.resource_limits().max_samples = 0;  // unlimited overall; bounded per instance
}

bool is_ipv4(const std::string& text) {
  in_addr address{};
  return ::inet_pton(AF_INET, text.c_str(), &address) == 1;
}

std::vector<std::string> interface_addresses(const std::string& name) {
  std::vector<std::string> out;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return out;
  for (ifaddrs* it = list; it; it = it->ifa_next) {
    if (!it->ifa_addr || it->ifa_addr->sa_family != AF_INET || name != it->ifa_name) continue;
    char text[INET_ADDRSTRLEN] = {};
    const auto* in = reinterpret_cast<const sockaddr_in*>(it->ifa_addr);
    if (::inet_ntop(AF_INET, &in->sin_addr, text, sizeof text)) out.emplace_back(text);
  }
  ::freeifaddrs(list);
  return out;
}

Locator_t udp_locator(const std::string& address, std::uint32_t port) {
  Locator_t locator;
  locator.kind = LOCATOR_KIND_UDPv4;
  IPLocator::setIPv4(locator, address);
  locator.port = port;
  return locator;
}

eprosima::fastdds::rtps::RemoteServerAttributes discovery_server(const std::string& text, int id) {
  const auto colon = text.rfind(':');
  std::string host = colon == std::string::npos ? "" : text.substr(0, colon);
  if (host == "localhost") host = "127.0.0.1";
  int port = -1;
  if (colon != std::string::npos && colon + 1 < text.size() && text.size() - colon <= 6 &&
      std::all_of(text.begin() + static_cast<std::ptrdiff_t>(colon) + 1, text.end(),
                  [](char c) { return c >= '0' && c <= '9'; })) {
    port = std::stoi(text.substr(colon + 1));
  }
  if (!is_ipv4(host) || port < 1 || port > 65535) {
    throw std::invalid_argument("--discovery-server: expected IPV4:PORT[,IPV4:PORT...], got '" + text + "'");
  }
  eprosima::fastdds::rtps::RemoteServerAttributes server;
  eprosima::fastdds::rtps::get_server_client_default_guidPrefix(id, server.guidPrefix);
  server.metatrafficUnicastLocatorList.push_back(udp_locator(host, static_cast<std::uint32_t>(port)));
  return server;
}

}  // namespace

std::vector<std::string> resolve_interfaces(const std::vector<std::string>& interfaces) {
  if (interfaces.empty()) return {"127.0.0.1"};
  std::vector<std::string> out;
  for (const auto& entry : interfaces) {
    if (entry == "any") {
      if (interfaces.size() != 1) throw std::invalid_argument("--interface: 'any' stands alone");
      return {"any"};
    }
    if (entry.size() > 64) throw std::invalid_argument("--interface: entry longer than 64 characters");
    if (is_ipv4(entry)) {
      out.push_back(entry);
      continue;
    }
    const auto addresses = interface_addresses(entry);
    if (addresses.empty()) {
      throw std::invalid_argument("--interface: '" + entry +
                                  "' is neither an IPv4 address nor an interface with one on this "
                                  "host (expected e.g. 127.0.0.1, lo or eth0)");
    }
    out.insert(out.end(), addresses.begin(), addresses.end());
  }
  return out;
}

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

  std::optional<ParticipantIdentity> find(const std::string& prefix) const {
    std::lock_guard lock(mutex_);
    const auto it = known_.find(prefix);
    if (it == known_.end()) return std::nullopt;
    return it->second;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, ParticipantIdentity> known_;
};

std::optional<ParticipantIdentity> DdsContext::participant_identity(
    const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) const {
  return participants_->find(prefix_text(prefix));
}

namespace {

// Fast DDS's built-in security plugins (PKI-DH authentication, access control with signed
// governance and permissions, AES-GCM): the standard participant properties.
void add_security_properties(DomainParticipantQos& qos, const std::string& directory, const std::string& identity) {
  const std::filesystem::path dir = std::filesystem::absolute(directory);
  const auto file = [&](const std::string& name) {
    const auto path = dir / name;
    if (!std::filesystem::is_regular_file(path)) {
      throw std::invalid_argument("--security: " + path.string() + " not found (scripts/make-lab-pki.sh makes it)");
    }
    return "file://" + path.string();
  };
  auto& properties = qos.properties().properties();
  properties.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_ca", file("ca.pem"));
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_certificate", file(identity + ".pem"));
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.private_key", file(identity + ".key"));
  properties.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions_ca", file("ca.pem"));
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.governance", file("governance.p7s"));
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions", file("permissions.p7s"));
  properties.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

}  // namespace

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
    participant_ = factory->create_participant_with_profile(options.domain_id, options.participant_profile,
                                                            participants_.get(), StatusMask::none());
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

    const std::vector<std::string> addresses = resolve_interfaces(options.interfaces);
    const bool any = addresses.size() == 1 && addresses[0] == "any";
    const bool loopback_only =
        !any && std::all_of(addresses.begin(), addresses.end(),
                            [](const std::string& a) { return a.rfind("127.", 0) == 0; });
    auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
    if (!any) udp->interfaceWhiteList = addresses;
    udp->maxInitialPeersRange = kMaxLoopbackParticipants;
    qos.transport().use_builtin_transports = false;
    if (options.transport == Transport::builtin) {
      qos.transport().user_transports.push_back(
          std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>());
    }
    qos.transport().user_transports.push_back(udp);

    std::string where;
    for (const auto& a : addresses) where += (where.empty() ? "" : ",") + a;
    if (!options.discovery_servers.empty()) {
      builtin.discovery_config.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::CLIENT;
      int id = 0;
      std::string servers;
      for (const auto& text : options.discovery_servers) {
        builtin.discovery_config.m_DiscoveryServers.push_back(discovery_server(text, id++));
        servers += (servers.empty() ? "" : ",") + text;
      }
      // The client's own discovery traffic stays on the chosen interface, not a multicast group.
      builtin.metatrafficMulticastLocatorList.clear();
      if (!any) {
        builtin.metatrafficUnicastLocatorList.clear();
        builtin.metatrafficUnicastLocatorList.push_back(udp_locator(addresses[0], 0));
      }
      where += ", discovery server " + servers;
    } else if (loopback_only) {
      // Loopback has no multicast: find the other participants of this host by unicast on
      // the well-known ports of the first kMaxLoopbackParticipants participant ids, and bind
      // nothing to a wildcard or multicast address.
      builtin.metatrafficMulticastLocatorList.clear();
      builtin.metatrafficUnicastLocatorList.clear();
      builtin.metatrafficUnicastLocatorList.push_back(udp_locator(addresses[0], 0));
      qos.wire_protocol().default_unicast_locator_list.clear();
      qos.wire_protocol().default_unicast_locator_list.push_back(udp_locator(addresses[0], 0));
      builtin.initialPeersList.clear();
      builtin.initialPeersList.push_back(udp_locator(addresses[0], 0));
      where += ", unicast discovery";
    } else {
      where += ", multicast discovery";
    }
    transport_description_ = std::string(options.transport == Transport::udp ? "UDPv4" : "shared memory + UDPv4") +
                             " on " + (any ? std::string("every interface") : where);
    if (!options.security_dir.empty()) {
      add_security_properties(qos, options.security_dir, options.name);
      transport_description_ += ", DDS Security as " + options.name;
    }
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
    apply(qos, delivery);
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
    apply(qos, delivery);
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

bool wait_for_readers(DataWriter* writer, int count, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  PublicationMatchedStatus status;
  while (std::chrono::steady_clock::now() < deadline) {
    writer->get_publication_matched_status(status);
    if (status.current_count >= count) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

std::chrono::system_clock::time_point received_at(const SampleInfo& info) {
  const auto& stamp = info.reception_timestamp;
  if (stamp.seconds() <= 0) return std::chrono::system_clock::now();
  return std::chrono::system_clock::time_point(std::chrono::duration_cast<std::chrono::system_clock::duration>(
      std::chrono::seconds(stamp.seconds()) + std::chrono::nanoseconds(stamp.nanosec())));
}

}  // namespace netmc::dds
