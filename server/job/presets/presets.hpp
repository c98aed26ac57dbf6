#pragma once
// Named studies: a list of jobs run side by side, and the paper's table to print beside them.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "idl/job.pb.h"

namespace netmc::presets {

struct PaperRow {
  std::string controller;  // the run's label, or its controller name
  double e_max_m;          // paper 001: e_max and e_sum; steady studies: RMS and max
  double e_sum_m;
};

struct StudyPlan {
  std::string title;
  std::vector<netmc::v1::JobSpec> jobs;
  std::vector<PaperRow> paper;      // empty when the study has no paper reference
  std::string paper_source;
  // Judged after the start-up transient: the table shows the steady RMS and max (um).
  bool steady_metrics = false;
};

std::vector<std::string> preset_names();
// Throws std::invalid_argument("--preset: ...") for an unknown name.
StudyPlan make_preset(std::string_view name);

// Paper 001's experiment (Table 1): circle r = 10 mm at (50, 50) mm, 8 s, h = 5 ms, loop delay
// uniform 0.3..0.8 ms, plant seed001, for `controller`.
netmc::v1::JobSpec seed001_job(const std::string& controller);

}  // namespace netmc::presets
