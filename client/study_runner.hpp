#pragma once
// Runs the jobs of a study in-process (virtual time), one worker thread per core.

#include <functional>
#include <vector>

#include "client/study_plan.hpp"
#include "server/sim/iteration_metrics.hpp"

namespace netmc::cli {

// Which per-cycle traces a study keeps: none (the CLI's tables), the last iteration's (the CLI's
// --csv and --plot), or every iteration's (the Python package's Study.trace).
enum class TraceRecording { none, last_iteration, every_iteration };

struct RunOutcome {
  netmc::v1::RunResult result;
  std::vector<sim::CycleTrace> last_trace;   // per-cycle trace of the last iteration (last_iteration)
  std::vector<std::vector<sim::CycleTrace>> iteration_traces;  // every iteration's (every_iteration)
  std::vector<control::EstimateName> estimate_names;  // the trace's controller estimates
};

// Builds every job first, so a bad spec fails before anything runs (std::invalid_argument).
// Jobs are taken by the workers in order and each result lands at its job's index, so the
// outcome does not depend on the thread count. `on_iteration` (optional) is called from the
// worker threads after each iteration; it must be thread-safe.
std::vector<RunOutcome> run_study_in_process(const StudyPlan& plan, TraceRecording traces,
                                             unsigned worker_threads,
                                             const std::function<void()>& on_iteration = {});

}  // namespace netmc::cli
