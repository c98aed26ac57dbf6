#pragma once
// The netmc topics (architecture.md, "DDS data plane"), versioned with the types in
// idl/dds_types.idl. Realtime and lockstep commands travel on topics of their own because their
// QoS differ: a realtime stream never waits for a lost sample, a lockstep exchange needs every one.

namespace netmc::dds {

inline constexpr const char* kJobControlTopic = "netmc/v2/job_control";
inline constexpr const char* kAxisEventTopic = "netmc/v2/axis_event";
inline constexpr const char* kRealtimeSetpointTopic = "netmc/v2/realtime/setpoint";
inline constexpr const char* kRealtimeFeedbackTopic = "netmc/v2/realtime/feedback";
inline constexpr const char* kLockstepSetpointTopic = "netmc/v2/lockstep/setpoint";
inline constexpr const char* kLockstepFeedbackTopic = "netmc/v2/lockstep/feedback";
inline constexpr const char* kIterationLogTopic = "netmc/v2/iteration_log";
inline constexpr const char* kNodeStatusTopic = "netmc/v2/node_status";
inline constexpr const char* kClockProbeTopic = "netmc/v2/clock_probe";
inline constexpr const char* kClockReplyTopic = "netmc/v2/clock_reply";

}  // namespace netmc::dds
