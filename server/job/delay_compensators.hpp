#pragma once
// The delay compensators a job may name (JobSpec.compensation, --compensate), one descriptor each
// as controllers have theirs: its name and syntax, what it does, where it comes from, and which
// laws it works with. --help, --list-compensators, the spec check and the docs' table
// (docs/user-guide/delay-compensation.md) take them from here.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "idl/job.pb.h"
#include "server/job/controller_registry.hpp"
#include "server/sim/contour_job.hpp"

namespace netmc::job {

struct DelayCompensatorDescriptor {
  std::string name;     // as --compensate and JobSpec.compensation.name take it
  std::string syntax;   // the flag's form
  std::string summary;  // one line: what it does
  std::string model;    // what it predicts with
  std::string source;   // by the short names of docs/references.md
};

// Commands per setpoint of packets when the spec names none.
inline constexpr std::uint32_t kDefaultHorizon = 8;
// Every compensator, "none" first.
const std::vector<DelayCompensatorDescriptor>& delay_compensators();
// "none | predictor" for --compensate's help.
std::string delay_compensator_syntax();
// A Markdown table of the compensators (netmc sim --list-compensators).
std::string delay_compensators_markdown_table();
// --compensate's text (NAME or NAME:horizon=N,playout=DURATION|bound) as a spec: unset for "none". Throws
// std::invalid_argument naming `flag`.
std::optional<netmc::v1::CompensationSpec> parse_compensation(std::string_view text, std::string_view flag);
// The spec as --compensate writes it ("predictor+packets:horizon=8"), for results and labels.
std::string compensation_text(const netmc::v1::CompensationSpec& spec);
// Whether the compensator carries a horizon of commands (packetized predictive control).
bool takes_horizon(std::string_view name);
// Whether it plans a delay, and so takes a playout delay ("playout=DURATION|bound").
bool takes_playout(std::string_view name);
// The compensation of a job (unset when the spec names none): the compensator checked and the
// prediction model of every axis taken from the controller's law. Throws std::invalid_argument
// ("compensation: ...") for an unknown compensator or a law that cannot predict.
std::optional<sim::DelayCompensation> build_compensation(const netmc::v1::JobSpec& spec,
                                                         const sim::JobReference& reference,
                                                         const std::vector<std::string>& axis_names);

}  // namespace netmc::job
