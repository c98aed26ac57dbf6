#pragma once
// One controller family as netmc knows it: its names, the gains it reads (its own group, and any
// shared one such as task_space), what it is and where it comes from (for --help and the docs'
// table), the plants its defaults are tuned for, and how it is built. A family is one file under
// server/job/controllers/ and one line in controllers/registered_controllers.inc; --help, spec checking, netmc
// sim, netmc-server and the docs' table (netmc sim --list-controllers) take it from there.
//
// Roles: an axis law (one per axis: adrc, pid) composes with a contour compensator (pidccc,
// ilccc, ...) as AXIS[+COMPENSATOR] into a cross-coupled planar controller; a group law builds
// the whole group's controller itself (the task-space laws, paper 002's, paper 004's ffpid, which
// takes a compensator too); a tracking law controls a single-axis group.

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "control/axis/axis_controller.hpp"
#include "control/group/contour_group.hpp"
#include "control/cross_coupling/contour_compensator.hpp"
#include "control/delay_compensation/prediction_model.hpp"
#include "server/job/controller_gains.hpp"
#include "server/sim/contour_job.hpp"

namespace netmc::job {

enum class ControllerRole { axis, compensator, group, tracking };

// What a family builds from.
struct ControllerContext {
  const GainsReader& gains;
  double sample_period_s = 0.0;
  const sim::JobReference& reference;
  std::string estimator;  // the cross-coupled controllers' contour-error estimator ("" curvature)

  std::size_t axis_count() const { return gains.axis_names().size(); }
};

struct ControllerFamily {
  std::vector<std::string> names;          // "gtcf-sarc", "ltcf-sarc": one law, several names
  ControllerRole role = ControllerRole::group;
  std::string summary;                     // one line: what it is
  std::string source;                      // where it comes from, by the short names of docs/references.md
  std::vector<std::string> gain_groups;    // the groups it reads ("adrc"; "task_space" shared)
  std::vector<std::string> plants;         // the plants its defaults are tuned for (none: required_gains)
  bool takes_compensator = false;          // group laws that compose with +COMPENSATOR (ffpid)
  // Keys of the family's first gains group a spec must give: where no default makes a working
  // controller, the controller is refused without them (the message names the flag).
  std::vector<std::string> required_gains;
  std::string required_why;                // why, for that message

  // ControllerRole::axis: the law of axis `axis` of the group.
  std::function<std::unique_ptr<control::AxisController>(const ControllerContext&, std::size_t axis)> make_axis;
  // The model a delay compensator predicts axis `axis` with (--compensate predictor): the law's
  // own where it has one (ADRC: its observer's). Unset: the law cannot predict, and a job that
  // asks it to is refused naming it.
  std::function<control::PredictionModel(const ControllerContext&, std::size_t axis)> prediction_model;
  // ControllerRole::compensator.
  std::function<std::unique_ptr<control::ContourCompensator>(const ControllerContext&)> make_compensator;
  // ControllerRole::group and ::tracking: the group's controller under `name` (one of names),
  // with `compensator` (null unless takes_compensator and one was named).
  std::function<std::unique_ptr<control::GroupController>(const ControllerContext&, std::string_view name,
                                                          std::unique_ptr<control::ContourCompensator> compensator)>
      make_group;
};

}  // namespace netmc::job
