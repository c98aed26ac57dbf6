#include "client/realtime_study_length.hpp"

#include <fmt/format.h>

#include <cmath>

#include "server/job/job_builder.hpp"

namespace netmc::cli {
namespace {

std::string minutes_and_seconds(double seconds) {
  const auto total = static_cast<long>(std::ceil(seconds));
  if (total < 60) return fmt::format("{} s", total);
  return fmt::format("{} min {} s", total / 60, total % 60);
}

}  // namespace

RealtimeStudyLength realtime_study_length(const std::vector<netmc::v1::JobSpec>& jobs) {
  RealtimeStudyLength length;
  for (const auto& spec : jobs) {
    if (spec.clock() != "realtime") continue;
    const auto job = job::build_contour_job(spec, job::check_without_files());
    ++length.jobs;
    length.iterations += job.iterations;
    length.motion_s += job.run_length_s() * static_cast<double>(job.iterations);
  }
  return length;
}

std::optional<std::string> realtime_study_notice(const std::vector<netmc::v1::JobSpec>& jobs) {
  const RealtimeStudyLength length = realtime_study_length(jobs);
  if (length.jobs == 0) return std::nullopt;
  std::string notice = fmt::format("realtime: {} job{}, {} iterations, {} of motion at the least", length.jobs,
                                   length.jobs == 1 ? "" : "s", length.iterations,
                                   minutes_and_seconds(length.motion_s));
  // Past a minute a first-time user wonders whether anything happens: offer the short variant.
  if (length.motion_s > 60.0) notice += "; for a first try: --controller adrc --iterations 2";
  return notice;
}

}  // namespace netmc::cli
