#pragma once
// Runs the ILC iterations of a ContourJob in virtual time: axis nodes sample on their clock,
// feedback crosses the uplink, the server computes each cycle when the feedback of every axis
// has arrived or its deadline has passed, setpoints cross the downlink and act on arrival.
// Deterministic for a given seed.

#include <functional>
#include <vector>

#include "control/contouring_controller.hpp"
#include "netsim/delayed_channel.hpp"
#include "server/sim/contour_job.hpp"
#include "server/sim/iteration_metrics.hpp"
#include "server/sim/simulated_axis.hpp"

namespace netmc::sim {

class ContourJobRunner {
 public:
  explicit ContourJobRunner(ContourJob job);

  IterationRecord run_iteration();                 // the next iteration
  // All remaining iterations; `on_iteration` (optional) sees each as it completes.
  std::vector<IterationRecord> run_all(
      const std::function<void(const IterationRecord&)>& on_iteration = {});

  const ContourJob& job() const { return job_; }
  std::size_t completed_iterations() const { return completed_; }
  std::string controller_description() const { return controller_.describe(); }

 private:
  ContourJob job_;
  control::ContouringController controller_;
  std::vector<SimulatedAxis> axes_;
  std::vector<netsim::DelayedChannel<double>> uplinks_;    // measured position
  std::vector<netsim::DelayedChannel<double>> downlinks_;  // command
  std::size_t completed_ = 0;
};

}  // namespace netmc::sim
