#pragma once
// How long a realtime study takes, said before it starts: on the wall clock the axes move through
// every iteration at the trajectory's own pace (the default study: 4 runs x 20 iterations x 8 s).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "idl/job.pb.h"

namespace netmc::cli {

struct RealtimeStudyLength {
  std::size_t jobs = 0;        // the jobs on the wall clock (clock "realtime"); lockstep ones are not counted
  std::size_t iterations = 0;  // theirs, all together
  double motion_s = 0.0;       // iterations x each run's length: the least the study can take
};

// Checks each job as the client does before sending it (std::invalid_argument naming the field).
RealtimeStudyLength realtime_study_length(const std::vector<netmc::v1::JobSpec>& jobs);

// "realtime: 4 jobs, 80 iterations, 10 min 40 s of motion at the least; for a first try: ...",
// or nothing when no job runs on the wall clock.
std::optional<std::string> realtime_study_notice(const std::vector<netmc::v1::JobSpec>& jobs);

}  // namespace netmc::cli
