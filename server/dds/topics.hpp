#pragma once
// The netmc topics of the DDS data plane (QoS per kind in server/dds/dds_context.hpp), versioned with the types in
// idl/dds_types.idl. Realtime and lockstep commands travel on topics of their own because their
// QoS differ: a realtime stream never waits for a lost sample, a lockstep exchange needs every one.
// See docs/architecture.md, "DDS topics and QoS".

namespace netmc::dds {

inline constexpr const char* kJobControlTopic = "netmc/v3/job_control";
inline constexpr const char* kAxisEventTopic = "netmc/v3/axis_event";
inline constexpr const char* kRealtimeSetpointTopic = "netmc/v3/realtime/setpoint";
inline constexpr const char* kRealtimeFeedbackTopic = "netmc/v3/realtime/feedback";
inline constexpr const char* kLockstepSetpointTopic = "netmc/v3/lockstep/setpoint";
inline constexpr const char* kLockstepFeedbackTopic = "netmc/v3/lockstep/feedback";
inline constexpr const char* kIterationLogTopic = "netmc/v3/iteration_log";
inline constexpr const char* kNodeStatusTopic = "netmc/v3/node_status";
inline constexpr const char* kClockProbeTopic = "netmc/v3/clock_probe";
inline constexpr const char* kClockReplyTopic = "netmc/v3/clock_reply";

}  // namespace netmc::dds
