#pragma once
// Runs the ILC iterations of a ContourJob in-process, in virtual time, by wiring the axis-node
// side (AxisEndpoint) and the server side (ContourServer) with direct calls. netmc-server and
// netmc-axis wire the same two objects through DDS in lockstep mode. Deterministic for a seed.
// See docs/architecture.md, "One cycle through the code".

#include <functional>
#include <vector>

#include "server/sim/axis_endpoint.hpp"
#include "server/sim/contour_job.hpp"
#include "server/sim/contour_server.hpp"
#include "server/sim/iteration_metrics.hpp"

namespace netmc::sim {

class ContourJobRunner {
 public:
  explicit ContourJobRunner(ContourJob job);

  IterationRecord run_iteration();                 // the next iteration
  // All remaining iterations (stopping after an unstable one); `on_iteration` (optional) sees
  // each as it completes.
  std::vector<IterationRecord> run_all(
      const std::function<void(const IterationRecord&)>& on_iteration = {});

  const ContourJob& job() const { return job_; }
  std::size_t completed_iterations() const { return completed_; }
  std::string controller_description() const { return server_.controller_description(); }

 private:
  ContourJob job_;
  ContourServer server_;
  std::vector<AxisEndpoint> axes_;
  std::size_t completed_ = 0;
};

}  // namespace netmc::sim
