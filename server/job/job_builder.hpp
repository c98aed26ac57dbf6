#pragma once
// The edge between the control plane (protobuf JobSpec / RunResult) and the pure job runner.
// Every field is checked here; errors are std::invalid_argument naming the field.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "idl/job.pb.h"
#include "server/job/controller_registry.hpp"
#include "server/sim/contour_job.hpp"
#include "server/sim/iteration_metrics.hpp"

namespace netmc::job {

// The names of the axes a job drives, in the group's order (spec.axes; default x for one axis,
// x, y for two, x, y, z for three), checked.
std::vector<std::string> axis_names(const netmc::v1::JobSpec& spec);
// Gives the job's axes new names, in group order, and moves what named the old ones (plant_axes,
// the dead-zone inverse, per-axis gains) with them. Throws std::invalid_argument ("axes: ...").
void rename_axes(netmc::v1::JobSpec& spec, const std::vector<std::string>& names);
// Which axis of the named plant set axis `axis` of a job is: its place in the group, but a job of
// one axis named y (or z) runs the plant's Y (Z) axis (thesis 5.5 identifies each contouring
// axis's dead zone on its own).
std::size_t plant_axis_index(const std::vector<std::string>& axis_names, std::size_t axis);
// An axis or node name: 1-64 characters of A-Z a-z 0-9 _ . - (std::invalid_argument naming `field`).
void check_name(const std::string& name, const std::string& field);
// Fills the defaults of paper 001 where the spec leaves a field unset.
void apply_defaults(netmc::v1::JobSpec& spec);
// Limits of a spec (docs/operations/hostile-networks-and-clients.md, "Job spec limits"); the other scalar fields' ranges are there too.
inline constexpr std::size_t kMaxJobNameBytes = 256;
// A realtime job's contour-error limit where its spec names none: this share of the reference's
// size (the larger side of the box it sweeps): 5 mm on paper 001's 20 mm circle. Far beyond any
// tracking result, far short of the 50 mm divergence limit a run could reach unsupervised.
inline constexpr double kRealtimeContourErrorLimitShare = 0.25;
inline constexpr std::uint32_t kMaxIterations = 10000;

// What a process builds of a job it does not run whole. A plant or controller read from a file
// (FMU, plugin) is only opened where it runs: on the axis node for the plant, on the server for
// the controller, and there only if the operator allowed it.
struct JobBuildOptions {
  // false: a plant read from a file gets stand-ins that refuse to be simulated (a server, a
  // client checking the job it sends); netmc's own plants are built as always.
  bool load_plant_files = true;
  ControllerPluginPolicy controller_plugins;
};

// A check of a job that runs elsewhere (a client before it sends it): every field, but no file
// of a plant or controller opened.
inline JobBuildOptions check_without_files() {
  JobBuildOptions options;
  options.load_plant_files = false;
  options.controller_plugins.load = false;
  return options;
}

// Builds the runnable job, one, two or three axes (loads delay trace files a local spec names,
// checks every field against its documented range).
sim::ContourJob build_contour_job(const netmc::v1::JobSpec& spec, const JobBuildOptions& options = {});
// A spec from the network names no file: throws std::invalid_argument naming the field of a
// delay trace given by path. Servers and axis nodes call it before anything else.
void reject_file_references(const netmc::v1::JobSpec& spec);
// A local spec made fit to send: delay traces named by path are read into delays_s (bounded as
// load_delay_trace_csv bounds them) and their paths dropped.
void inline_delay_traces(netmc::v1::JobSpec& spec);
// A three-axis contour (trajectory.spatial_circle, thesis ch. 6).
bool is_spatial_job(const netmc::v1::JobSpec& spec);
// The longest delay a profile ever draws (a truncated normal or pareto's max, a trace's longest);
// nullopt for a profile without one (untruncated normal or pareto, a trace not yet loaded).
std::optional<double> delay_profile_bound_s(const netmc::v1::DelayProfile& delay);
// A single-axis tracking job (trajectory.multi_sine, thesis ch. 5).
bool is_single_axis_job(const netmc::v1::JobSpec& spec);
// The axes the job's group drives: 1, 2 or 3.
std::size_t group_axis_count(const netmc::v1::JobSpec& spec);

std::string describe_trajectory(const netmc::v1::Trajectory& trajectory);
std::string describe_link(const netmc::v1::LinkProfile& link);

netmc::v1::IterationMetrics to_proto(const sim::IterationMetrics& metrics);
// A RunResult with the description of `spec` filled in and no iterations yet.
netmc::v1::RunResult describe_run(const netmc::v1::JobSpec& spec,
                                  const std::string& controller_detail);

// JSON through protobuf's JSON mapping, field names as in job.proto (a 0.1 spec's typed gains
// upgraded first, legacy_spec.hpp).
netmc::v1::JobSpec parse_job_spec_json(const std::string& json, const std::string& origin);
std::string to_json(const google::protobuf::Message& message);

}  // namespace netmc::job
