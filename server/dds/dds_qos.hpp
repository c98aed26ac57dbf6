#pragma once
// The QoS of each kind of netmc data (Delivery), applied to a writer's or reader's QoS; see
// docs/architecture.md.

#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

namespace netmc::dds {

//   stream    best-effort, keep-last: realtime setpoints and feedback never wait for a lost
//             sample; the axis holds its last command, the server computes with what it has.
//   exchange  reliable with millisecond heartbeats: lockstep, where every sample is needed and a
//             lost one is repaired after one heartbeat period instead of Fast DDS's default 3 s.
//   control   the same reliability for job control and axis events (rare, must not be lost).
//   log       reliable, transient-local, keep-last 64 per job.
//   status    reliable, transient-local, keep-last 1 per node.
enum class Delivery { stream, exchange, control, log, status };

// Lab-size limits (docs/operations/distributed-runs.md): instances per keyed topic, i.e. axes, nodes,
// or jobs whose iteration logs a reader keeps.
inline constexpr int kMaxInstances = 4096;

void apply_delivery_qos(eprosima::fastdds::dds::DataWriterQos& qos, Delivery delivery);
void apply_delivery_qos(eprosima::fastdds::dds::DataReaderQos& qos, Delivery delivery);

}  // namespace netmc::dds
