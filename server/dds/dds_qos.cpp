#include "server/dds/dds_qos.hpp"

namespace netmc::dds {
namespace {

using namespace eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;

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

}  // namespace

void apply_delivery_qos(DataWriterQos& qos, Delivery delivery) { apply(qos, delivery); }
void apply_delivery_qos(DataReaderQos& qos, Delivery delivery) { apply(qos, delivery); }

}  // namespace netmc::dds
