#pragma once
// The named studies (server/job/presets/) under the names the CLI's code uses for them.

#include "server/job/presets/presets.hpp"

namespace netmc::cli {

using presets::make_preset;
using presets::PaperRow;
using presets::preset_names;
using presets::seed001_job;
using presets::StudyPlan;

}  // namespace netmc::cli
