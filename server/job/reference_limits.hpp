#pragma once
// The physical ranges of every number of a job's reference (docs/operations/hostile-networks-and-clients.md, "Job spec limits"): a
// reference outside them describes no motion a lab stage makes, and numbers such as 1e308 m or a
// 1e-300 s period only overflow or divide by nothing downstream.

#include <string>

#include "idl/job.pb.h"

namespace netmc::job {

// The workspace: every coordinate of a reference (centre, point, start, end, offset) within
// +-kWorkspaceM, every length (radius, semi-axis, amplitude) at most kWorkspaceM.
inline constexpr double kWorkspaceM = 10.0;
// The shortest length a radius or semi-axis may have: a contour a sensor can resolve.
inline constexpr double kMinContourLengthM = 1e-6;
// A period (or a motion's duration) spans at least this many sample periods, a sine at most
// 1 / (this many sample periods) hertz: fewer samples do not describe the motion.
inline constexpr double kMinSamplesPerPeriod = 10.0;
// The longest period or motion: the run length limit.
inline constexpr double kMaxPeriodS = 1e6;
// Angles and phases: |value| at most this many radians.
inline constexpr double kMaxAngleRad = 100.0;
inline constexpr double kMaxRevolutions = 1e6;
// Speeds, accelerations and jerks: at least kMinSpeedMS in their unit (slower is no motion).
inline constexpr double kMinSpeedMS = 1e-6;
inline constexpr double kMaxSpeedMS = 10.0;
inline constexpr double kMaxAccelerationMS2 = 1e4;
inline constexpr double kMaxJerkMS3 = 1e7;

// Throws std::invalid_argument naming the field (as in job.proto, under "trajectory.") and its
// expected range. `sample_period_s` 0 (unset) skips the checks relative to it.
void check_reference_limits(const netmc::v1::Trajectory& trajectory, double sample_period_s);

}  // namespace netmc::job
