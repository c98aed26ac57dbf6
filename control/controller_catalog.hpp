#pragma once
// Contouring controllers chosen by name: AXIS[+COMPENSATOR], e.g. "adrc", "adrc+ilccc".

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "control/axis/adrc_controller.hpp"
#include "control/axis/tracking_controller.hpp"
#include "control/axis/feedforward_pid_axis.hpp"
#include "control/cross_coupling/contouring_controller.hpp"
#include "control/data_driven/compact_form_mfac.hpp"
#include "control/dead_zone/adaptive_variable_structure_controller.hpp"
#include "control/dead_zone/dead_zone_diarc.hpp"
#include "control/dead_zone/fixed_inverse_diarc.hpp"
#include "control/data_driven/mfa_dtsmc_axis.hpp"
#include "control/frequency/qft_bounds.hpp"
#include "control/cross_coupling/iterative_learning_cross_coupling.hpp"
#include "control/axis/pid_axis_controller.hpp"
#include "control/cross_coupling/pid_cross_coupling.hpp"
#include "control/task_space/spatial_sarc.hpp"
#include "control/task_space/task_space_adrc.hpp"
#include "control/task_space/task_space_cogging_darc.hpp"
#include "control/task_space/task_space_darc.hpp"
#include "control/task_space/task_space_diarc.hpp"
#include "control/task_space/task_space_sarc.hpp"

namespace netmc::control {

// Defaults are paper 001's gains (sec. 1.6 of the digest).
struct ControllerSettings {
  AdrcGains adrc;
  // The y axis's ADRC when it differs from the x axis's (axes of different mass: b0 = 1/M).
  std::optional<AdrcGains> adrc_y;
  PidAxisGains pid;
  PidCrossCouplingGains pidccc;
  IterativeLearningGains ilccc;
  SarcGains sarc;
  GtcfAdrcGains gtcf_adrc;
  DarcGains darc;
  DiarcGains diarc;
  CoggingDarcGains cogging_darc;  // thesis ch. 4 (gtcf-darc-cogging, ltcf-darc-cogging)
  SpatialSarcGains spatial_sarc;  // three-axis GTCF-SARC (thesis ch. 6)
  // Thesis eq. 2-67, for the task-space controllers in the global frame (gtcf-*).
  InitializationFilterSettings initialization_filter;
  // How the local-frame controllers (ltcf-*) differentiate their error.
  LocalFrameRate local_frame_rate = LocalFrameRate::frozen;
  // Paper 002's data-driven laws (mfa-dtsmc = C4, mfac = C3); the y axis's when set.
  MfaDtsmcGains mfa_dtsmc;
  std::optional<MfaDtsmcGains> mfa_dtsmc_y;
  CompactFormMfacGains mfac;
  std::optional<CompactFormMfacGains> mfac_y;
  std::optional<PidAxisGains> pid_y;
  // Paper 004 (ffpid): the per-axis loops of eq. 2 with feedforward, Tables 1 and 2, and the
  // PID-type cross-coupling of eq. 13 (lpccc), Table 3.
  FeedforwardPidGains ffpid_x = paper004_x_axis_gains();
  FeedforwardPidGains ffpid_y = paper004_y_axis_gains();
  FilteredPidCrossCouplingGains lpccc;
  // Thesis ch. 5 (one axis): the DIARC loop (5-22) of C1-C4, the dead zone C4 inverts (volts,
  // the thesis's Exp I by default) and the adaptive variable-structure law of C5.
  DiarcLoopGains axis_diarc;
  DeadZoneEstimate exact_dead_zone = thesis_dead_zone_inverse(DeadZoneHandling::exact_inverse);
  DeadZoneDiarcGains dead_zone_diarc;  // C3's estimator (its `loop` is axis_diarc)
  AdaptiveVariableStructureGains avsc;
  // Thesis section 5.5: a fixed dead-zone inverse per axis of the group, in order, between the
  // controller and the axes (volts); empty: none.
  std::vector<DeadZoneEstimate> dead_zone_inverse;
  std::string estimator = "curvature";
};

std::vector<std::string> axis_controller_names();        // adrc, pid
std::vector<std::string> contour_compensator_names();    // pidccc, ilccc, lpccc, qftccc
// Throws std::invalid_argument("controller: ...") for an unknown name or invalid gain.
// `trajectory` is needed by the foot-point estimators (settings.estimator newton, steffensen).
ContouringController make_contouring_controller(std::string_view name,
                                                const ControllerSettings& settings,
                                                double sample_period_s,
                                                std::shared_ptr<const ReferenceTrajectory> trajectory = nullptr);

// Every controller by name: AXIS[+COMPENSATOR] as above, or a task-space contouring controller
// gtcf-sarc / ltcf-sarc (thesis ch. 2), gtcf-darc / ltcf-darc / gtcf-diarc / ltcf-diarc
// (thesis ch. 3), gtcf-darc-cogging / ltcf-darc-cogging (thesis ch. 4) or gtcf-adrc (task-space ADRC) on the contour of `trajectory`, or paper 002's
// data-driven contouring mfa-dtsmc / mfac, or paper 004's per-axis loops with acceleration
// feedforward, ffpid[+COMPENSATOR] (ffpid, ffpid+lpccc, ffpid+qftccc).
std::unique_ptr<ContourController> make_contour_controller(std::string_view name,
                                                           const ControllerSettings& settings,
                                                           double sample_period_s,
                                                           const ReferenceTrajectory& trajectory);

// Single-axis tracking controllers (thesis ch. 5, one-axis groups): axis-diarc (C1, the dead zone
// ignored), axis-diarc+nominal-inverse (C2), axis-diarc+exact-inverse (C4), axis-diarc-dead-zone
// (C3, the dead zone estimated) and axis-avsc (C5, the adaptive variable-structure law).
std::vector<std::string> tracking_controller_names();
// Throws std::invalid_argument("controller: ...") for an unknown name or invalid gain.
std::unique_ptr<TrackingController> make_tracking_controller(std::string_view name,
                                                             const ControllerSettings& settings,
                                                             double sample_period_s);

}  // namespace netmc::control
