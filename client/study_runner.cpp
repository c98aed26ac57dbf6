#include "client/study_runner.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <optional>
#include <thread>

#include "server/job/job_builder.hpp"
#include "server/sim/contour_job_runner.hpp"

namespace netmc::cli {

std::vector<RunOutcome> run_study_in_process(const StudyPlan& plan, TraceRecording traces,
                                             unsigned worker_threads,
                                             const std::function<void()>& on_iteration) {
  const bool record_traces = traces != TraceRecording::none;
  // Every job is built (and so checked) before any runs.
  std::vector<std::optional<sim::ContourJob>> jobs(plan.jobs.size());
  for (std::size_t i = 0; i < plan.jobs.size(); ++i) {
    jobs[i] = job::build_contour_job(plan.jobs[i]);
    jobs[i]->record_traces = record_traces;
  }

  std::vector<RunOutcome> outcomes(jobs.size());
  std::vector<std::exception_ptr> errors(jobs.size());
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i = next++; i < jobs.size(); i = next++) {
      try {
        const auto& spec = plan.jobs[i];
        RunOutcome& out = outcomes[i];
        sim::ContourJobRunner runner(std::move(*jobs[i]));
        out.result = job::describe_run(spec, runner.controller_description());
        // Iteration by iteration (as run_all, which keeps every record): a kept trace is moved,
        // not copied.
        const std::size_t iterations = runner.job().iterations;
        while (runner.completed_iterations() < iterations) {
          sim::IterationRecord record = runner.run_iteration();
          *out.result.add_iterations() = job::to_proto(record.metrics);
          if (record_traces) out.estimate_names = record.metrics.estimate_names;
          const bool diverged = record.metrics.diverged;
          if (traces == TraceRecording::every_iteration) {
            out.iteration_traces.push_back(std::move(record.trace));  // last_trace stays empty: the last of these
          } else if (record_traces) {
            out.last_trace = std::move(record.trace);
          }
          if (on_iteration) on_iteration();
          if (diverged) break;
        }
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  const unsigned threads = std::max(1u, std::min<unsigned>(worker_threads,
                                                           static_cast<unsigned>(jobs.size())));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  for (const auto& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  return outcomes;
}

}  // namespace netmc::cli
