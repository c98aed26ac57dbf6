#pragma once
// The drive under each axis of a node (netmc-axis --drive) and the limits the axis runs under.
// Hardware (a Modbus TCP drive, a lab's plugin) is opened at the node's start and kept for its
// life: an unreachable drive or a bad map refuses the start. netmc's simulated drive is made per
// job from the job's plant, with the node's own overrides on top (sim:PLANT:KEY=VALUE: the axis
// then differs from the model the job names, on purpose). Limits: the operator's flags, else the
// drive's own configuration (a map file), else, for a simulated drive, its plant's rating (travel
// and rated input). A drive that is not simulated must end up with a command limit, a position
// window and a velocity limit, or the node refuses to start.
// See docs/architecture.md, "Where safety lives".

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "idl/job.pb.h"
#include "server/drive/axis_limits.hpp"
#include "server/drive/drive.hpp"
#include "server/drive/drive_spec.hpp"
#include "server/sim/contour_job.hpp"

namespace netmc::axis {

struct AxisDrive {
  drive::DriveSpec spec;
  std::shared_ptr<drive::Drive> hardware;  // open; null for netmc's simulated drive
  drive::AxisLimits limits;
};

struct DriveSettings {
  double quick_stop_deceleration_m_s2 = 1.0;
};

// Opens every hardware drive of `specs` and resolves each axis's limits. Throws
// std::invalid_argument naming the flag, the axis and what is missing or wrong, and
// drive::DriveError for a drive that cannot be reached or answers wrongly.
std::map<std::string, AxisDrive> open_axis_drives(const std::map<std::string, drive::DriveSpec>& specs,
                                                  const std::map<std::string, drive::AxisLimits>& flag_limits,
                                                  const DriveSettings& settings);

// The plant model a node's jobs name: --plant if given, else its simulated drives' (they name one
// plant), else seed001. Throws std::invalid_argument when these disagree.
std::string node_plant(const std::map<std::string, drive::DriveSpec>& specs, const std::string& plant_flag);

// `spec` with the node's overrides of a simulated drive added to `axis`'s plant parameters.
netmc::v1::JobSpec with_node_overrides(netmc::v1::JobSpec spec, const std::string& axis, const AxisDrive& drive);

// The drive a job's axis `index` runs on: the hardware, or a fresh simulated drive of the job's
// plant for that axis.
std::shared_ptr<drive::Drive> job_drive(const AxisDrive& drive, const sim::ContourJob& job, std::size_t index,
                                        const DriveSettings& settings);

}  // namespace netmc::axis
