#include "server/dds/dds_context.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>

#include <filesystem>
#include <thread>

namespace netmc::dds {
namespace {

using namespace eprosima::fastdds::dds;

template <typename Qos>
void apply(Qos& qos, Delivery delivery) {
  // Samples with sequences (job spec, applied setpoints) may outgrow the preallocated size.
  qos.endpoint().history_memory_policy =
      eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  switch (delivery) {
    case Delivery::control:
      // Reliable; keep-last 64 per axis rather than keep-all: lockstep has at most one sample
      // per axis in flight, and keep-all would fill the writer history (400 per instance)
      // between acknowledgements, which come only with the heartbeat.
      qos.reliability().kind = RELIABLE_RELIABILITY_QOS;
      qos.durability().kind = VOLATILE_DURABILITY_QOS;
      qos.history().kind = KEEP_LAST_HISTORY_QOS;
      qos.history().depth = 64;
      break;
    case Delivery::log:
      qos.reliability().kind = RELIABLE_RELIABILITY_QOS;
      qos.durability().kind = TRANSIENT_LOCAL_DURABILITY_QOS;
      qos.history().kind = KEEP_LAST_HISTORY_QOS;
      qos.history().depth = 64;
      break;
    case Delivery::status:
      qos.reliability().kind = RELIABLE_RELIABILITY_QOS;
      qos.durability().kind = TRANSIENT_LOCAL_DURABILITY_QOS;
      qos.history().kind = KEEP_LAST_HISTORY_QOS;
      qos.history().depth = 1;
      qos.liveliness().kind = AUTOMATIC_LIVELINESS_QOS;
      break;
  }
}

}  // namespace

DdsContext::DdsContext(const DdsOptions& options) {
  auto* factory = DomainParticipantFactory::get_instance();
  if (!options.xml_profile_file.empty() && !std::filesystem::is_regular_file(options.xml_profile_file)) {
    throw std::invalid_argument("--dds-profile: no such file '" + options.xml_profile_file + "'");
  }
  if (!options.xml_profile_file.empty() &&
      factory->load_XML_profiles_file(options.xml_profile_file) != ReturnCode_t::RETCODE_OK) {
    throw std::invalid_argument("--dds-profile: cannot load Fast DDS XML profiles from '" +
                                options.xml_profile_file + "'");
  }
  xml_loaded_ = !options.xml_profile_file.empty();
  if (!options.participant_profile.empty()) {
    participant_ = factory->create_participant_with_profile(options.domain_id,
                                                            options.participant_profile);
    transport_description_ = "XML profile " + options.participant_profile;
  } else {
    DomainParticipantQos qos = PARTICIPANT_QOS_DEFAULT;
    qos.name(options.name);
    if (options.transport == Transport::udp) {
      qos.transport().use_builtin_transports = false;
      qos.transport().user_transports.push_back(
          std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>());
      transport_description_ = "UDPv4 only";
    } else {
      transport_description_ = "Fast DDS built-in (shared memory + UDPv4)";
    }
    participant_ = factory->create_participant(options.domain_id, qos);
  }
  if (!participant_) {
    throw std::runtime_error("dds: cannot create a participant in domain " +
                             std::to_string(options.domain_id));
  }
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

DataWriter* DdsContext::writer(Topic* topic, Delivery delivery) {
  DataWriterQos qos = DATAWRITER_QOS_DEFAULT;
  // An XML <data_writer profile_name="TOPIC"> replaces the built-in QoS of that topic.
  if (!xml_loaded_ ||
      publisher_->get_datawriter_qos_from_profile(topic->get_name(), qos) != ReturnCode_t::RETCODE_OK) {
    qos = DATAWRITER_QOS_DEFAULT;
    apply(qos, delivery);
  }
  auto* created = publisher_->create_datawriter(topic, qos);
  if (!created) throw std::runtime_error("dds: cannot create a writer for " + topic->get_name());
  return created;
}

DataReader* DdsContext::reader(Topic* topic, Delivery delivery) {
  DataReaderQos qos = DATAREADER_QOS_DEFAULT;
  // An XML <data_reader profile_name="TOPIC"> replaces the built-in QoS of that topic.
  if (!xml_loaded_ ||
      subscriber_->get_datareader_qos_from_profile(topic->get_name(), qos) != ReturnCode_t::RETCODE_OK) {
    qos = DATAREADER_QOS_DEFAULT;
    apply(qos, delivery);
  }
  auto* created = subscriber_->create_datareader(topic, qos);
  if (!created) throw std::runtime_error("dds: cannot create a reader for " + topic->get_name());
  return created;
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

}  // namespace netmc::dds
