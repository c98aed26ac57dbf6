#include "control/controller_catalog.hpp"

#include <stdexcept>

#include "control/cross_coupling/feedforward_pid_contouring.hpp"
#include "control/cross_coupling/tustin_cross_coupling.hpp"
#include "control/data_driven/data_driven_contouring.hpp"

namespace netmc::control {
namespace {

std::string usage() {
  return "expected mfa-dtsmc, mfac, gtcf-sarc, ltcf-sarc, gtcf-darc, ltcf-darc, gtcf-diarc, ltcf-diarc, "
         "gtcf-darc-cogging, ltcf-darc-cogging, gtcf-adrc, AXIS or "
         "AXIS+COMPENSATOR with AXIS one of adrc, pid, ffpid and "
         "COMPENSATOR one of pidccc, ilccc, lpccc, qftccc (paper 004: ffpid uncoupled, ffpid+lpccc eq. 13, "
         "ffpid+qftccc eq. 20)";
}

std::unique_ptr<AxisController> make_axis(std::string_view name, const ControllerSettings& s,
                                          double h) {
  if (name == "adrc") return std::make_unique<AdrcController>(s.adrc, h);
  if (name == "pid") return std::make_unique<PidAxisController>(s.pid, h);
  return nullptr;
}

std::unique_ptr<ContourCompensator> make_compensator(std::string_view name,
                                                     const ControllerSettings& s, double h) {
  if (name.empty()) return std::make_unique<NoContourCompensation>();
  if (name == "pidccc") return std::make_unique<PidCrossCoupling>(s.pidccc, h);
  if (name == "ilccc") return std::make_unique<IterativeLearningCrossCoupling>(s.ilccc, h);
  if (name == "lpccc") return std::make_unique<TustinCrossCoupling>(make_low_pass_pid_cross_coupling(s.lpccc, h));
  if (name == "qftccc") return std::make_unique<TustinCrossCoupling>(make_qft_cross_coupling(h));
  return nullptr;
}

// Paper 004: ffpid[+COMPENSATOR]; its axes need the reference acceleration, so it is a
// controller of its own rather than an AXIS of ContouringController.
std::unique_ptr<ContourController> make_feedforward_pid_contouring(std::string_view name,
                                                                   const ControllerSettings& settings,
                                                                   double sample_period_s,
                                                                   const ReferenceTrajectory& trajectory) {
  const std::size_t plus = name.find('+');
  const std::string_view compensator_name = plus == std::string_view::npos ? std::string_view{} : name.substr(plus + 1);
  auto compensator = make_compensator(compensator_name, settings, sample_period_s);
  if (!compensator || (plus != std::string_view::npos && compensator_name.empty())) {
    throw std::invalid_argument("controller: unknown name '" + std::string(name) + "' (" + usage() + ")");
  }
  return std::make_unique<FeedforwardPidContouring>(settings.ffpid_x, settings.ffpid_y, sample_period_s,
                                                    make_contour_error_estimator(settings.estimator, trajectory.clone()),
                                                    std::move(compensator));
}

}  // namespace

std::vector<std::string> axis_controller_names() { return {"adrc", "pid"}; }
std::vector<std::string> contour_compensator_names() { return {"pidccc", "ilccc", "lpccc", "qftccc"}; }

ContouringController make_contouring_controller(std::string_view name,
                                                const ControllerSettings& settings,
                                                double sample_period_s,
                                                std::shared_ptr<const ReferenceTrajectory> trajectory) {
  const std::size_t plus = name.find('+');
  const std::string_view axis_name = name.substr(0, plus);
  const std::string_view compensator_name =
      plus == std::string_view::npos ? std::string_view{} : name.substr(plus + 1);
  auto x_axis = make_axis(axis_name, settings, sample_period_s);
  auto compensator = make_compensator(compensator_name, settings, sample_period_s);
  if (!x_axis || !compensator || (plus != std::string_view::npos && compensator_name.empty())) {
    throw std::invalid_argument("controller: unknown name '" + std::string(name) + "' (" +
                                usage() + ")");
  }
  std::unique_ptr<AxisController> y_axis;
  if (axis_name == "adrc" && settings.adrc_y) {
    y_axis = std::make_unique<AdrcController>(*settings.adrc_y, sample_period_s);
  } else if (axis_name == "pid" && settings.pid_y) {
    y_axis = std::make_unique<PidAxisController>(*settings.pid_y, sample_period_s);
  } else {
    y_axis = x_axis->clone();
  }
  return ContouringController(std::move(x_axis), std::move(y_axis),
                              make_contour_error_estimator(settings.estimator, std::move(trajectory)),
                              std::move(compensator));
}

std::unique_ptr<ContourController> make_contour_controller(std::string_view name,
                                                           const ControllerSettings& settings,
                                                           double sample_period_s,
                                                           const ReferenceTrajectory& trajectory) {
  const auto& filter = settings.initialization_filter;
  if (name == "mfa-dtsmc" || name == "mfac") {
    std::unique_ptr<DataDrivenAxisLaw> x, y;
    if (name == "mfa-dtsmc") {
      x = std::make_unique<MfaDtsmcAxis>(settings.mfa_dtsmc, sample_period_s);
      y = std::make_unique<MfaDtsmcAxis>(settings.mfa_dtsmc_y.value_or(settings.mfa_dtsmc), sample_period_s);
    } else {
      x = std::make_unique<CompactFormMfacAxis>(settings.mfac);
      y = std::make_unique<CompactFormMfacAxis>(settings.mfac_y.value_or(settings.mfac));
    }
    return std::make_unique<DataDrivenContouring>(
        std::move(x), std::move(y), make_contour_error_estimator(settings.estimator, trajectory.clone()),
        sample_period_s);
  }
  if (name == "gtcf-sarc") {
    return std::make_unique<TaskSpaceSarc>(settings.sarc, sample_period_s, make_task_frame(trajectory), filter);
  }
  if (name == "gtcf-adrc") {
    return std::make_unique<TaskSpaceAdrc>(settings.gtcf_adrc, sample_period_s, make_task_frame(trajectory));
  }
  if (name == "ltcf-sarc") return std::make_unique<TaskSpaceSarc>(settings.sarc, sample_period_s, nullptr, filter, settings.local_frame_rate);
  if (name == "gtcf-darc-cogging") {
    return std::make_unique<TaskSpaceCoggingDarc>(settings.cogging_darc, sample_period_s, make_task_frame(trajectory),
                                                  filter);
  }
  if (name == "ltcf-darc-cogging") {
    return std::make_unique<TaskSpaceCoggingDarc>(settings.cogging_darc, sample_period_s, nullptr, filter,
                                                  settings.local_frame_rate);
  }
  if (name == "gtcf-darc") {
    return std::make_unique<TaskSpaceDarc>(settings.darc, sample_period_s, make_task_frame(trajectory), filter);
  }
  if (name == "ltcf-darc") return std::make_unique<TaskSpaceDarc>(settings.darc, sample_period_s, nullptr, filter, settings.local_frame_rate);
  if (name == "gtcf-diarc") {
    return std::make_unique<TaskSpaceDiarc>(settings.diarc, sample_period_s, make_task_frame(trajectory), filter);
  }
  if (name == "ltcf-diarc") return std::make_unique<TaskSpaceDiarc>(settings.diarc, sample_period_s, nullptr, filter, settings.local_frame_rate);
  if (name == "ffpid" || name.starts_with("ffpid+")) return make_feedforward_pid_contouring(name, settings, sample_period_s, trajectory);
  return std::make_unique<ContouringController>(
      make_contouring_controller(name, settings, sample_period_s, trajectory.clone()));
}

std::vector<std::string> tracking_controller_names() {
  return {"axis-diarc", "axis-diarc+nominal-inverse", "axis-diarc+exact-inverse", "axis-diarc-dead-zone", "axis-avsc"};
}

std::unique_ptr<TrackingController> make_tracking_controller(std::string_view name, const ControllerSettings& settings,
                                                             double sample_period_s) {
  try {
    if (name == "axis-diarc-dead-zone") {
      DeadZoneDiarcGains gains = settings.dead_zone_diarc;
      gains.loop = settings.axis_diarc;
      return std::make_unique<DeadZoneDiarc>(gains, sample_period_s);
    }
    if (name == "axis-avsc") return std::make_unique<AdaptiveVariableStructureController>(settings.avsc, sample_period_s);
    const std::pair<std::string_view, DeadZoneHandling> fixed[] = {
        {"axis-diarc", DeadZoneHandling::ignored},
        {"axis-diarc+nominal-inverse", DeadZoneHandling::nominal_inverse},
        {"axis-diarc+exact-inverse", DeadZoneHandling::exact_inverse}};
    for (const auto& [known, handling] : fixed) {
      if (name != known) continue;
      auto gains = FixedInverseDiarcGains::thesis(handling);
      gains.loop = settings.axis_diarc;
      if (handling == DeadZoneHandling::exact_inverse) gains.inverse = settings.exact_dead_zone;
      return std::make_unique<FixedInverseDiarc>(gains, sample_period_s);
    }
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    if (message.rfind("controller", 0) == 0) throw;
    throw std::invalid_argument("controller: " + message);
  }
  std::string expected;
  for (const auto& known : tracking_controller_names()) expected += (expected.empty() ? "" : ", ") + known;
  std::string message = "controller: a single-axis job runs one of ";
  message.append(expected).append(", got '").append(name).append("'");
  throw std::invalid_argument(message);
}

}  // namespace netmc::control
