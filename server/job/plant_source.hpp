#pragma once
// Where a job's plant comes from: netmc's catalog (seed001, linmotor, ...), an FMU
// (fmu:PATH.fmu[:KEY=VALUE,...], server/fmu) or a component plugin (plugin:PATH.so[:KEY=VALUE,...],
// server/plugins). The whole text is the plant's name in a spec: a node hosting an FMU plant
// names the same text, and its options are the file's, not the catalog's KEY=VALUE overrides.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "plant/plant_catalog.hpp"

namespace netmc::job {

using plant::is_file_plant;  // fmu:, plugin:

// The plant set of `name` for `axis_count` axes; throws std::invalid_argument naming what is wrong.
plant::AxisSet make_job_plant_set(std::string_view name, std::size_t axis_count,
                                  const std::vector<plant::AxisOverrides>& overrides = {});

// The plant's per-axis parameters and its input's unit (an FMU's from its modelDescription.xml;
// a plugin's parameters are its own to check: none listed, unit "input").
std::vector<plant::PlantParameter> job_plant_parameters(std::string_view name);
std::string job_plant_input_unit(std::string_view name);

// Stand-ins for a plant another process holds (a server's view of an FMU or plugin plant that
// the axis nodes run, a client checking a job it sends): as many axes as the job has, each
// refusing to be simulated.
plant::AxisSet remote_plant_set(std::string_view name, std::size_t axis_count);

}  // namespace netmc::job
