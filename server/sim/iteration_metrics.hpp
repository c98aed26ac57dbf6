#pragma once
// Per-iteration results of a contouring job, SI units: contour errors from the true plant state and the exact
// distance to the reference, tracking and command per axis, loop delays and message counts.

#include <cstddef>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "control/group/contour_group.hpp"

namespace netmc::sim {

struct IterationMetrics {
  std::size_t iteration = 0;             // 1-based
  double e_max_m = 0.0;                  // max |eps| over the samples (exact contour error)
  double e_rms_m = 0.0;
  double e_sum_m = 0.0;                  // sum of |eps(k)| (paper 001's cumulative error)
  double e_rms_steady_m = 0.0;           // over the evaluation window (after the start-up)
  double e_max_steady_m = 0.0;
  std::size_t steady_samples = 0;        // samples in the evaluation window; 0: no steady metrics
  // Per axis, in the group's order.
  std::vector<double> tracking_rms_m;
  std::vector<double> tracking_max_m;
  std::vector<double> command_rms;
  // Over the evaluation window, of the command as the axis applies it (limited to command_limit).
  std::vector<double> command_rms_steady;
  double tau_mean_s = 0.0;               // loop delay t_arrival(setpoint k) - t_k
  double tau_p50_s = 0.0;
  double tau_p99_s = 0.0;
  double tau_max_s = 0.0;
  // The parts of tau: sensor -> controller (incl. waiting for the slowest axis's feedback),
  // computation, controller -> actuator.
  double tau_sc_mean_s = 0.0, tau_sc_p99_s = 0.0, tau_sc_max_s = 0.0;
  double tau_cc_mean_s = 0.0, tau_cc_p99_s = 0.0, tau_cc_max_s = 0.0;
  double tau_ca_mean_s = 0.0, tau_ca_p99_s = 0.0, tau_ca_max_s = 0.0;
  std::uint64_t deadline_misses = 0;     // cycles computed without fresh feedback of every axis
  std::uint64_t lost_feedback = 0;
  std::uint64_t late_feedback = 0;       // came after its cycle's deadline (used later if newest)
  std::uint64_t lost_setpoints = 0;
  std::uint64_t stale_setpoints = 0;     // arrived after a newer one, dropped
  bool diverged = false;                 // the loop went unstable; metrics cover samples before
  // The axes did not follow the reference: an axis covered less than half of the range its
  // reference spans (contour_server.cpp). The contour error of a closed curve is the distance to
  // the whole curve, so axes standing on it show e_max 0: such a run is no result.
  bool did_not_follow = false;
  double diverged_at_s = 0.0;
  // Where a limit stopped the iteration (the contour-error limit): what crossed it, when, where.
  std::string stop_reason;
  double clock_uncertainty_s = 0.0;      // distributed realtime: +- on tau_sc / tau_ca
  // With a delay compensator only: the age of the newest feedback of each axis when a cycle was
  // computed (compute time - sample time), over the cycles and axes.
  bool compensated = false;
  double feedback_age_mean_s = 0.0, feedback_age_p99_s = 0.0, feedback_age_max_s = 0.0;
  // With packets only (packetized predictive control), summed over the axes: cycles played from
  // an older setpoint's horizon, and cycles the last command was held (horizon exhausted).
  bool packets = false;
  std::uint64_t horizon_cycles = 0, held_cycles = 0;
  // The controller's internal estimates (adaptive parameters, observer states) and their values
  // after the iteration's last cycle; empty for a controller without any.
  std::vector<control::EstimateName> estimate_names;
  std::vector<double> final_estimates;
};

// One sample of a per-cycle trace (for --csv); per-axis values in the group's order.
struct CycleTrace {
  double time_s = 0.0;
  control::AxisVector reference_m;
  control::AxisVector position_m;
  control::AxisVector measured_m;
  double contour_error_m = 0.0;
  double contour_error_estimate_m = 0.0;
  control::AxisVector axis_command;
  control::AxisVector command;
  double coupling_command = 0.0;
  double tau_s = -1.0;                   // of axis x; -1 when its setpoint was lost
  // The first IterationMetrics::estimate_names.size() are the controller's estimates.
  std::array<double, control::kMaxControllerEstimates> estimates{};
};

struct IterationRecord {
  IterationMetrics metrics;
  std::vector<CycleTrace> trace;         // empty unless the job records traces
};

}  // namespace netmc::sim
