// Paper 004's per-axis loops (eq. 2) with acceleration feedforward, ffpid[+COMPENSATOR]: its
// axes need the reference acceleration, so it is a group law of its own rather than an AXIS of
// the cross-coupled composition. Each axis's defaults are its table (x: Table 1, y: Table 2).
#include "control/axis/feedforward_pid_axis.hpp"
#include "control/contour_error/contour_error_estimator.hpp"
#include "control/cross_coupling/feedforward_pid_contouring.hpp"
#include "control/group/planar_contour_group.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {

void register_feedforward_pid(ControllerRegistry& registry) {
  registry.add(GainGroup{
      "ffpid", "--ffpid", "Paper 004's per-axis loops; defaults: Table 1 (x), Table 2 (y)", true,
      {{"mass_kg", "moving mass m (kg): sets K_p and the feedforward", "24 (x), 30 (y)", GainKey::Kind::number,
        GainCheck::positive},
       {"bandwidth_hz", "loop bandwidth f_bw (Hz)", "50", GainKey::Kind::number, GainCheck::positive},
       {"alpha", "corner spacing alpha", "3", GainKey::Kind::number, GainCheck::positive},
       {"low_pass_damping", "damping z_lp of G_c's low-pass", "0.7", GainKey::Kind::number, GainCheck::positive},
       {"feedforward_fraction", "feedforward as a fraction of m r''", "0.85"}}});
  ControllerFamily family;
  family.names = {"ffpid"};
  family.role = ControllerRole::group;
  family.takes_compensator = true;
  family.summary = "per-axis feedback G_c with acceleration feedforward; +lpccc or +qftccc couple the axes";
  family.source = "paper 004, eq. 2, Tables 1-2";
  family.gain_groups = {"ffpid"};
  family.plants = {"stage004"};
  family.make_group = [](const ControllerContext& context, std::string_view name,
                         std::unique_ptr<control::ContourCompensator> compensator)
      -> std::unique_ptr<control::GroupController> {
    const auto* trajectory = std::get_if<std::shared_ptr<const control::ReferenceTrajectory>>(&context.reference);
    if (!trajectory) throw std::invalid_argument("controller: " + std::string(name) + " runs two-axis contours only");
    control::FeedforwardPidGains axes[2] = {control::paper004_x_axis_gains(), control::paper004_y_axis_gains()};
    for (std::size_t axis = 0; axis < 2; ++axis) {
      auto& gains = axes[axis];
      const auto& g = context.gains;
      g.read("ffpid", "mass_kg", axis, gains.mass_kg);
      g.read("ffpid", "bandwidth_hz", axis, gains.bandwidth_hz);
      g.read("ffpid", "alpha", axis, gains.alpha);
      g.read("ffpid", "low_pass_damping", axis, gains.low_pass_damping);
      g.read("ffpid", "feedforward_fraction", axis, gains.feedforward_fraction);
    }
    if (!compensator) compensator = std::make_unique<control::NoContourCompensation>();
    return std::make_unique<control::PlanarGroupController>(std::make_unique<control::FeedforwardPidContouring>(
        axes[0], axes[1], context.sample_period_s,
        control::make_contour_error_estimator(context.estimator.empty() ? "curvature" : context.estimator,
                                              (*trajectory)->clone()),
        std::move(compensator)));
  };
  registry.add(std::move(family));
}

}  // namespace netmc::job
