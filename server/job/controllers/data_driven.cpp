// Paper 002's data-driven contouring laws: MFA-DTSMC (C4: a data model estimated online with a
// discrete terminal sliding mode) and CFDL-MFAC (C3), per axis with the contour error's weight.
// Gains in the paper's units (lengths in um).
#include <stdexcept>

#include "control/contour_error/contour_error_estimator.hpp"
#include "control/data_driven/compact_form_mfac.hpp"
#include "control/data_driven/data_driven_contouring.hpp"
#include "control/data_driven/mfa_dtsmc_axis.hpp"
#include "control/group/planar_contour_group.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::job {
namespace {

GainKey number(const char* name, const char* meaning, const char* default_text) {
  return GainKey{name, meaning, default_text};
}

GainKey data_model() {
  return GainKey{"data_model",
                 "compact (paper 002, eq. 9) or full (a full-form data model, L_y = 2, d = 1: not the paper's)",
                 "compact", GainKey::Kind::choice, GainCheck::finite, {"compact", "full"}};
}

control::DataModelForm form_of(const GainsReader& g, const char* group, std::size_t axis, control::DataModelForm form) {
  const auto choice = g.choice(group, "data_model", axis);
  return choice ? control::parse_data_model_form(*choice, g.field(group, "data_model", axis)) : form;
}

std::unique_ptr<control::GroupController> data_driven_group(const ControllerContext& context, std::string_view name,
                                                            std::unique_ptr<control::DataDrivenAxisLaw> x,
                                                            std::unique_ptr<control::DataDrivenAxisLaw> y) {
  const auto* trajectory = std::get_if<std::shared_ptr<const control::ReferenceTrajectory>>(&context.reference);
  if (!trajectory) throw std::invalid_argument("controller: " + std::string(name) + " runs two-axis contours only");
  return std::make_unique<control::PlanarGroupController>(std::make_unique<control::DataDrivenContouring>(
      std::move(x), std::move(y),
      control::make_contour_error_estimator(context.estimator.empty() ? "curvature" : context.estimator,
                                            (*trajectory)->clone()),
      context.sample_period_s));
}

}  // namespace

void register_data_driven(ControllerRegistry& registry) {
  registry.add(GainGroup{"mfa_dtsmc", "--mfa-dtsmc", "Paper 002's MFA-DTSMC (C4) gains, lengths in um", true,
                         {number("mu", "Phi^ penalty mu", "0.5"), number("eta", "Phi^ step eta", "0.8"),
                          number("lambda_s", "switching gain", "0.5"), number("lambda1", "sliding gain lambda1", "0.3"),
                          number("lambda2", "sliding gain lambda2", "0.2"),
                          number("alpha", "terminal exponent alpha (odd ratio in (0, 1))", "5/7"),
                          number("beta", "beta", "0.75"), number("sigma", "dd^ step sigma", "0.8"),
                          number("gamma", "Psi^ penalty gamma", "0.4"), number("tau", "Psi^ step tau", "0.8"),
                          number("rho", "dd^ penalty rho", "0.3"), number("delta", "contour-error weight of eq. 16", "20"),
                          number("q", "q (1/s), 0 < 1 - qT < 1", "500"), number("delta1", "delta1", "0.25"),
                          number("delta2", "delta2", "0.25"), number("epsilon", "reset threshold", "1e-5"),
                          number("lambda", "reaching gain", "0.04"),
                          number("phi_initial", "initial Phi^ (um/V)", "18"),
                          number("psi_initial", "initial Psi^ (um/V)", "18"),
                          number("d0", "disturbance bound (V)", "1"), data_model()}});
  registry.add(GainGroup{"mfac", "--mfac", "Paper 002's CFDL-MFAC (C3) gains, lengths in um", true,
                         {number("mu", "mu", "0.5"), number("lambda", "lambda", "0.1"), number("rho", "rho", "0.6"),
                          number("eta", "eta", "1"), number("epsilon", "epsilon", "1e-5"),
                          number("delta", "contour-error weight", "20"),
                          number("phi_initial", "initial PPD estimate (um/V)", "18"), data_model()}});

  ControllerFamily dtsmc;
  dtsmc.names = {"mfa-dtsmc"};
  dtsmc.role = ControllerRole::group;
  dtsmc.summary = "model-free adaptive discrete terminal sliding mode contouring (C4)";
  dtsmc.source = "paper 002, eqs. 9-24";
  dtsmc.gain_groups = {"mfa_dtsmc"};
  // No plant: paper 002's gains diverge on netmc's sampled ball screw with either data model.
  dtsmc.plants = {};
  dtsmc.required_gains = {"data_model"};
  dtsmc.required_why = "with paper 002's gains neither form holds a netmc plant (compact, the paper's eq. 9, and full both diverge on the sampled ball screw within 20 ms; full holds the paper's own eq. 2; docs/reproductions/paper-002.md, Paper 002's data-driven controllers), so the form is the spec's choice";
  dtsmc.make_group = [](const ControllerContext& context, std::string_view name,
                        std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    const auto axis_law = [&](std::size_t axis) {
      control::MfaDtsmcGains g;
      const auto& r = context.gains;
      auto& e = g.estimator;
      auto& t = g.sliding;
      const char* group = "mfa_dtsmc";
      r.read(group, "mu", axis, e.mu);
      r.read(group, "eta", axis, e.eta);
      r.read(group, "sigma", axis, e.sigma);
      r.read(group, "gamma", axis, e.gamma);
      r.read(group, "tau", axis, e.tau);
      r.read(group, "rho", axis, e.rho);
      r.read(group, "epsilon", axis, e.epsilon);
      r.read(group, "phi_initial", axis, e.phi_initial);
      r.read(group, "psi_initial", axis, e.psi_initial);
      r.read(group, "d0", axis, e.disturbance_bound);
      r.read(group, "lambda1", axis, t.lambda1);
      r.read(group, "lambda2", axis, t.lambda2);
      r.read(group, "alpha", axis, t.alpha);
      r.read(group, "beta", axis, t.beta);
      r.read(group, "q", axis, t.q);
      r.read(group, "delta1", axis, t.delta1);
      r.read(group, "delta2", axis, t.delta2);
      r.read(group, "lambda", axis, t.lambda);
      r.read(group, "lambda_s", axis, g.switching_gain);
      r.read(group, "delta", axis, g.contour_weight);
      g.data_model = form_of(r, group, axis, g.data_model);
      return std::make_unique<control::MfaDtsmcAxis>(g, context.sample_period_s);
    };
    return data_driven_group(context, name, axis_law(0), axis_law(1));
  };
  registry.add(std::move(dtsmc));

  ControllerFamily mfac;
  mfac.names = {"mfac"};
  mfac.role = ControllerRole::group;
  mfac.summary = "compact-form dynamic-linearization model-free adaptive contouring (C3)";
  mfac.source = "paper 002";
  mfac.gain_groups = {"mfac"};
  mfac.plants = {};  // as mfa-dtsmc
  mfac.required_gains = {"data_model"};
  mfac.required_why = "with paper 002's gains neither form holds a netmc plant (compact, the paper's eq. 9, and full both diverge on the sampled ball screw within 20 ms; full holds the paper's own eq. 2; docs/reproductions/paper-002.md, Paper 002's data-driven controllers), so the form is the spec's choice";
  mfac.make_group = [](const ControllerContext& context, std::string_view name,
                       std::unique_ptr<control::ContourCompensator>) -> std::unique_ptr<control::GroupController> {
    const auto axis_law = [&](std::size_t axis) {
      control::CompactFormMfacGains g;
      const auto& r = context.gains;
      r.read("mfac", "mu", axis, g.mu);
      r.read("mfac", "lambda", axis, g.lambda);
      r.read("mfac", "rho", axis, g.rho);
      r.read("mfac", "eta", axis, g.eta);
      r.read("mfac", "epsilon", axis, g.epsilon);
      r.read("mfac", "delta", axis, g.contour_weight);
      r.read("mfac", "phi_initial", axis, g.phi_initial);
      g.data_model = form_of(r, "mfac", axis, g.data_model);
      return std::make_unique<control::CompactFormMfacAxis>(g);
    };
    return data_driven_group(context, name, axis_law(0), axis_law(1));
  };
  registry.add(std::move(mfac));
}

}  // namespace netmc::job
