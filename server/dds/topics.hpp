#pragma once
// The netmc topics of the DDS data plane (QoS per kind in server/dds/dds_context.hpp), versioned with the types in
// idl/dds_types.idl. Realtime and lockstep commands travel on topics of their own because their
// QoS differ: a realtime stream never waits for a lost sample, a lockstep exchange needs every one.
// See docs/architecture.md, "DDS topics and QoS".

namespace netmc::dds {

inline constexpr const char* kJobControlTopic = "netmc/v4/job_control";
inline constexpr const char* kAxisEventTopic = "netmc/v4/axis_event";
inline constexpr const char* kRealtimeSetpointTopic = "netmc/v4/realtime/setpoint";
inline constexpr const char* kRealtimeFeedbackTopic = "netmc/v4/realtime/feedback";
inline constexpr const char* kLockstepSetpointTopic = "netmc/v4/lockstep/setpoint";
inline constexpr const char* kLockstepFeedbackTopic = "netmc/v4/lockstep/feedback";
inline constexpr const char* kIterationLogTopic = "netmc/v4/iteration_log";
inline constexpr const char* kNodeStatusTopic = "netmc/v4/node_status";
inline constexpr const char* kClockProbeTopic = "netmc/v4/clock_probe";
inline constexpr const char* kClockReplyTopic = "netmc/v4/clock_reply";

}  // namespace netmc::dds
