#pragma once
// Every controller family netmc runs, in one place: the built-in ones register here (one line
// each in controllers/registered_controllers.inc). The registry resolves a job's controller name
// (FAMILY, AXIS+COMPENSATOR, or plugin:PATH.so[:KEY=VALUE,...]), checks its gains against the
// families' declared keys, and writes the help and the docs' table.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "idl/job.pb.h"
#include "server/job/controller_family.hpp"
#include "server/job/controller_gains.hpp"

namespace netmc::job {

using ControllerFactory = std::function<std::unique_ptr<control::GroupController>()>;

// Which controller plugins (plugin:PATH.so) a process loads.
struct ControllerPluginPolicy {
  // false: the controller runs in another process (an axis node's view of a job, a client
  // checking the job it sends): a plugin's name and settings are checked, the file is not
  // opened, and the factory refuses to build.
  bool load = true;
  // The only paths a spec may name (a server: its --allow-plugin files); unset: any (a local spec).
  std::optional<std::vector<std::string>> allowed;
};

class ControllerRegistry {
 public:
  // The built-in families (and whatever was added since).
  static ControllerRegistry& global();

  void add(GainGroup group);
  void add(ControllerFamily family);

  const std::vector<GainGroup>& gain_groups() const { return groups_; }
  const std::vector<ControllerFamily>& families() const { return families_; }
  const GainGroup* gain_group(std::string_view name) const;
  const ControllerFamily* family(std::string_view name) const;

  // The factory of a job's controller, the name resolved and the gains checked, built once to
  // check what only the law itself can. Throws std::invalid_argument ("controller: ...", or the
  // field of a gain).
  ControllerFactory resolve(const netmc::v1::ControllerSpec& spec, const sim::JobReference& reference,
                            const std::vector<std::string>& axis_names, double sample_period_s,
                            const ControllerPluginPolicy& plugins = {}) const;

  // The law's own prediction model of each axis (group order) for a delay compensator; unset for a
  // law that has none (ControllerFamily::prediction_model).
  std::optional<std::vector<control::PredictionModel>> prediction_models(const netmc::v1::ControllerSpec& spec,
                                                          const sim::JobReference& reference,
                                                          const std::vector<std::string>& axis_names,
                                                          double sample_period_s) const;
  // The names of the laws that have a prediction model of their own.
  std::vector<std::string> predicting_laws() const;

  // "adrc, pid ... | AXIS+COMPENSATOR ..." for --controller's help.
  std::string names_help() const;
  // The laws of one axis on a tracking reference (ControllerRole::tracking), by name.
  std::vector<std::string> single_axis_names() const;
  // A Markdown table of every family: name, role, gains flag, source, tuned for, what it is.
  std::string markdown_table() const;

 private:
  ControllerFactory resolve_plugin(const netmc::v1::ControllerSpec& spec, const sim::JobReference& reference,
                                   const std::vector<std::string>& axis_names, double sample_period_s,
                                   const ControllerPluginPolicy& plugins) const;

  std::vector<GainGroup> groups_;
  std::vector<ControllerFamily> families_;
};

// Each built-in family file's registration (controllers/registered_controllers.inc).
#define NETMC_CONTROLLER(name) void register_##name(ControllerRegistry& registry);
#include "server/job/controllers/registered_controllers.inc"
#undef NETMC_CONTROLLER

}  // namespace netmc::job
