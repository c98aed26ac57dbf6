#pragma once
// A contouring job in plain C++ terms: what the job runner needs to run ILC iterations of one
// controller on one plant set over one network profile. Built from the protobuf JobSpec at the
// edge (server/job) so this layer stays free of protobuf and transport.

#include <Eigen/Dense>

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "control/group/contour_group.hpp"
#include "control/dead_zone/dead_zone_inverse.hpp"
#include "control/delay_compensation/prediction_model.hpp"
#include "control/trajectory/multi_sine_reference.hpp"
#include "control/trajectory/reference_trajectory.hpp"
#include "control/trajectory/spatial_circle.hpp"
#include "netsim/delay_model.hpp"
#include "netsim/loss_model.hpp"
#include "plant/axis_plant.hpp"
#include "plant/position_sensor.hpp"

namespace netmc::sim {

// One direction of the network between the server and every axis node (each axis gets its own
// independently seeded copy).
struct LinkProfile {
  std::shared_ptr<const netsim::DelayModel> delay = netsim::make_no_delay();
  std::shared_ptr<const netsim::LossModel> loss = netsim::make_no_loss();
  std::string describe() const;
};

// Start of the steady metrics' window: the requested start, or (0) after two periods of the
// reference, where the thesis judges its runs. Every job kind and the result description use it.
inline double resolve_evaluation_start(double requested_s, double reference_period_s) {
  return requested_s > 0.0 ? requested_s : 2.0 * reference_period_s;
}

// How the server compensates the loop's delay (JobSpec.compensation): the model of each axis in
// group order, whether the first command is planned over the measured delay (the state
// predictor), and how many commands each setpoint carries (packetized predictive control).
struct DelayCompensation {
  std::vector<control::PredictionModel> axis_models;  // one per axis
  bool predict_delay = true;     // "predictor": the command acts at the instant it was planned for
  std::size_t horizon = 1;       // commands per setpoint: 1, or "packets:horizon=N"
  double playout_s = 0.0;        // the least planned travel ("playout="); reports may plan longer
  static constexpr double kMaxPlayoutS = 60.0;  // netsim's bound on a delay: the longest travel planned
  static constexpr std::size_t kMaxHorizon = 64;  // bounds a setpoint sample and a node's buffer
};

// The reference a job's group follows: a planar trajectory (two axes), a circle in space (three
// axes, thesis ch. 6) or a single axis's tracking reference (one axis, thesis ch. 5).
using JobReference = std::variant<std::shared_ptr<const control::ReferenceTrajectory>,
                                  std::shared_ptr<const control::SpatialCircle>,
                                  std::shared_ptr<const control::MultiSineReference>>;
// How many coordinates the reference has: 2, 3 or 1.
std::size_t reference_dimension(const JobReference& reference);

// A contour group of one, two or three axes: one runner, one server loop and one data plane for
// all. Its axes are the job's (axis_names); the reference must have as many coordinates.
struct ContourJob {
  JobReference reference;
  std::vector<std::string> axis_names;  // in group order: the reference's x, y (, z)
  std::string plant_name;
  std::vector<std::shared_ptr<const plant::AxisPlant>> axes;  // prototypes, in group order
  std::string controller_name;
  // A fresh controller for the group (resolved and checked when the job was built).
  std::function<std::unique_ptr<control::GroupController>()> controller_factory;
  // Thesis section 5.5: a fixed dead-zone inverse per axis between the controller and the axes
  // (volts), in group order; empty: none.
  std::vector<control::DeadZoneEstimate> dead_zone_inverse;
  LinkProfile uplink;     // sensor -> controller (tau_sc)
  LinkProfile downlink;   // controller -> actuator (tau_ca)
  plant::PositionSensorParameters sensor;
  double sample_period_s = 0.005;
  double duration_s = 0.0;             // 0: the trajectory's duration
  std::size_t iterations = 1;
  std::uint64_t seed = 1;
  double deadline_s = 0.0;             // server waits this long for feedback; 0: one period
  double compute_delay_s = 0.0;        // tau_cc in virtual time
  double command_limit = std::numeric_limits<double>::infinity();  // |U| enforced at the axis
  // A run whose true contour error exceeds this (or whose command is not finite) is unstable:
  // the iteration stops there and is reported as diverged; later iterations are not run.
  double divergence_limit_m = 0.05;
  // The job's contour-error limit: beyond it the iteration stops at once with the crossing named
  // (IterationMetrics::stop_reason); a realtime job then fails, its axes quick-stopped. Infinity:
  // none.
  double contour_error_limit_m = std::numeric_limits<double>::infinity();
  // The larger side of the box the reference sweeps over the run (sampled every period).
  double reference_size_m() const;
  // Start of the evaluation window of the steady metrics; 0: after two periods of the reference.
  double evaluation_start_s = 0.0;
  double evaluation_start() const;
  // Where the axes rest at t = 0; unset: the trajectory's start (zero initial error).
  std::optional<control::AxisVector> initial_position;
  control::AxisVector start_position() const;
  bool record_traces = false;
  // Unset: no compensation, the loop as the papers run it.
  std::optional<DelayCompensation> compensation;

  // Throws std::invalid_argument naming the field when the job cannot run.
  void validate() const;
  std::size_t axis_count() const { return axis_names.size(); }
  // The group's contour and a fresh controller for it (with the dead-zone inverse, if any).
  std::shared_ptr<const control::GroupContour> contour() const;
  std::unique_ptr<control::GroupController> make_controller() const;
  double run_length_s() const;         // duration_s, or the reference's when 0
  std::size_t cycles() const;          // samples k = 0..N, so N + 1
  double deadline() const { return deadline_s > 0.0 ? deadline_s : sample_period_s; }
};

}  // namespace netmc::sim
