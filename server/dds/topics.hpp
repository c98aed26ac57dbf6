#pragma once
// The netmc topics (architecture.md, "DDS data plane"), versioned with the types in
// idl/dds_types.idl.

namespace netmc::dds {

inline constexpr const char* kSetpointTopic = "netmc/v1/setpoint";
inline constexpr const char* kFeedbackTopic = "netmc/v1/feedback";
inline constexpr const char* kIterationLogTopic = "netmc/v1/iteration_log";
inline constexpr const char* kNodeStatusTopic = "netmc/v1/node_status";

}  // namespace netmc::dds
