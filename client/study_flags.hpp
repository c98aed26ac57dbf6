#pragma once
// The study flags shared by `netmc sim` (in-process) and `netmc run` (against a server): a
// preset or JSON spec, overridden by flags, becomes a StudyPlan.

#include <CLI/CLI.hpp>

#include <map>
#include <string>
#include <vector>

#include "client/study_plan.hpp"

namespace netmc::cli {

struct StudyFlags {
  std::string preset;
  std::string spec_file;
  std::string trajectory, plant, controllers, delay, uplink_delay, loss, uplink_loss;
  std::string sample_period, duration, deadline, compute_delay, divergence_limit, command_limit;
  std::string contour_error_limit;
  // Each gains group's flag (--adrc, --ilc, --task-space, ...: the controller registry's), by group.
  std::map<std::string, std::string> gains;
  std::string adrc_y;  // --adrc-y: the second axis's ADRC (what --adrc y.KEY=.. says)
  std::string estimator, sensor, initial_position;
  int iterations = 0;
  long long seed = -1;
  std::vector<std::string> disturbances;  // --disturbance, one per axis
  std::vector<std::string> dead_zone_inverses;  // --dead-zone-inverse, one per axis
  std::string clock;
  std::string compensate;  // --compensate: a delay compensator (job::delay_compensators)
  std::string axes;
  std::string json_path;
  bool curve = false;
};

void add_study_flags(CLI::App* app, StudyFlags& flags);
// The flags that change every job of a study alike (plant, gains, period, iterations, links
// other than the downlink delay ...): shared with `netmc sweep`, whose grid axes replace the rest.
void add_job_override_flags(CLI::App* app, StudyFlags& flags);
// Throws std::invalid_argument naming the flag or field.
// --controller NAME[,NAME...]: the runs' controllers, a plugin's KEY=VALUE settings kept with it
// ("plugin:lib.so:kp=1,kd=2,adrc" is two runs).
std::vector<std::string> split_controller_list(const std::string& text);
StudyPlan plan_from_flags(const StudyFlags& flags);

}  // namespace netmc::cli
