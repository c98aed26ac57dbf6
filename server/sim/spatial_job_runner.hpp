#pragma once
// A three-axis contouring job (thesis, paper 000, ch. 6): GTCF-SARC on a circle in space, three
// simulated axes behind their downlinks, in virtual time. The axis side is the same AxisEndpoint
// the two-axis runner and netmc-axis use; the server side is the spatial controller itself.
// In-process only: the DDS data plane and its lockstep runner carry two-axis contour groups.

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "control/spatial_circle.hpp"
#include "control/spatial_sarc.hpp"
#include "plant/position_sensor.hpp"
#include "server/sim/axis_endpoint.hpp"
#include "server/sim/contour_job.hpp"

namespace netmc::sim {

struct SpatialJob {
  control::SpatialCircleParameters circle;
  double revolutions = 4.0;                   // run length
  control::SpatialSarcGains gains;
  std::string plant_name = "linmotor";        // three axes of it (the third copies Y)
  plant::PositionSensorParameters sensor;
  double command_limit = std::numeric_limits<double>::infinity();  // |U| enforced at each axis
  LinkProfile downlink;                       // controller -> actuator, per axis
  double sample_period_s = 2e-4;
  double evaluation_start_s = 0.0;            // steady metrics from here; 0: after two revolutions
  double divergence_limit_m = 0.05;
  std::uint64_t seed = 1;

  double duration_s() const { return revolutions * circle.period_s; }
  double evaluation_start() const { return resolve_evaluation_start(evaluation_start_s, circle.period_s); }
  // Throws std::invalid_argument naming the field when the job cannot run.
  void validate() const;
};

struct SpatialIterationMetrics {
  double e_max_m = 0.0;          // exact distance of the true position to the circle
  double e_rms_m = 0.0;
  double e_sum_m = 0.0;
  double e_rms_steady_m = 0.0;   // over the evaluation window
  double e_max_steady_m = 0.0;
  std::array<double, 3> tracking_rms_m{};
  std::array<double, 3> command_rms_steady{};  // of the command as the axis applies it
  double tau_mean_s = 0.0;       // setpoint arrival - sample time, every axis
  double tau_p99_s = 0.0;
  double tau_max_s = 0.0;
  std::uint64_t lost_setpoints = 0;
  std::uint64_t stale_setpoints = 0;
  bool diverged = false;
  double diverged_at_s = 0.0;
};

class SpatialJobRunner {
 public:
  explicit SpatialJobRunner(SpatialJob job);

  SpatialIterationMetrics run();  // one pass; the controller has no iteration-to-iteration memory
  std::string controller_description() const;
  const SpatialJob& job() const { return job_; }

 private:
  SpatialJob job_;
  std::shared_ptr<const control::SpatialCircle> circle_;
  std::vector<AxisEndpoint> axes_;
};

}  // namespace netmc::sim
