#include "client/study_flags.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "client/study_plan.hpp"
#include "client/spec_syntax.hpp"
#include "client/spec_validation.hpp"
#include "server/job/controller_registry.hpp"
#include "server/job/delay_compensators.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::cli {
namespace {

// A spec is a few kilobytes; the bound keeps a wrong path (/dev/zero, a log) from filling memory.
constexpr std::size_t kMaxSpecBytes = 4u << 20;

std::string read_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::invalid_argument("--spec: cannot read '" + path + "'");
  std::string content(kMaxSpecBytes + 1, '\0');
  file.read(content.data(), static_cast<std::streamsize>(content.size()));
  content.resize(static_cast<std::size_t>(file.gcount()));
  if (content.size() > kMaxSpecBytes) {
    throw std::invalid_argument("--spec: '" + path + "' is larger than 4 MiB (expected a JSON job spec)");
  }
  return content;
}

}  // namespace

std::vector<std::string> split_controller_list(const std::string& text) {
  std::vector<std::string> names;
  for (auto& item : split_list(text)) {
    // plugin:PATH.so:kp=1,kd=2: a KEY=VALUE after a plugin belongs to it, not to a run of its own
    // (no controller's name has an '=').
    if (!names.empty() && names.back().rfind("plugin:", 0) == 0 && item.find('=') != std::string::npos) {
      names.back() += "," + item;
    } else {
      names.push_back(std::move(item));
    }
  }
  return names;
}

StudyPlan plan_from_flags(const StudyFlags& f) {
  StudyPlan plan;
  if (!f.spec_file.empty()) {
    if (!f.preset.empty()) throw std::invalid_argument("--spec: cannot be combined with --preset");
    auto spec = parse_job_spec_file_text(read_file(f.spec_file), f.spec_file);
    plan.title = "job spec " + f.spec_file;
    plan.jobs.push_back(spec);
  } else {
    plan = make_preset(f.preset.empty() ? "seed001" : f.preset);
  }

  const bool changes_setup = !f.trajectory.empty() || !f.delay.empty() ||
                             !f.uplink_delay.empty() || !f.loss.empty() || !f.uplink_loss.empty() ||
                             !f.sample_period.empty() || !f.duration.empty() || !f.sensor.empty() ||
                             !f.initial_position.empty() || !f.disturbances.empty();
  if (changes_setup) {
    plan.paper.clear();
    plan.title = "custom study (based on " + (f.spec_file.empty() ? "preset " + (f.preset.empty() ? std::string("seed001") : f.preset) : f.spec_file) + ")";
  } else if (!f.plant.empty()) {
    // The same experiment on another model of the machine (linmotor-flex for linmotor): the
    // paper's figures stay beside it as the reference.
    plan.title += " -- plant " + f.plant;
  }

  if (!f.controllers.empty()) {
    const auto names = split_controller_list(f.controllers);
    if (names.empty()) throw std::invalid_argument("--controller: expected NAME[,NAME...]");
    const netmc::v1::JobSpec base = plan.jobs.front();
    plan.jobs.clear();
    for (const auto& name : names) {
      netmc::v1::JobSpec job = base;
      job.clear_name();  // labelled by its controller, not by the base job's label
      job.mutable_controller()->set_name(name);
      plan.jobs.push_back(job);
    }
  }

  for (auto& job : plan.jobs) {
    if (!f.trajectory.empty()) *job.mutable_trajectory() = parse_trajectory(f.trajectory);
    // The job's own overrides (a preset's payload, its disturbance) stay; the flag's are added
    // after them, and keys the new plant does not have are refused when the job is built.
    if (!f.plant.empty()) parse_plant(f.plant, job);
    for (const auto& disturbance : f.disturbances) parse_disturbance(disturbance, job);
    for (const auto& inverse : f.dead_zone_inverses) parse_dead_zone_inverse(inverse, job);
    if (!f.delay.empty()) *job.mutable_downlink()->mutable_delay() = parse_delay(f.delay, "--delay");
    if (!f.uplink_delay.empty()) {
      *job.mutable_uplink()->mutable_delay() = parse_delay(f.uplink_delay, "--uplink-delay");
    }
    if (!f.loss.empty()) *job.mutable_downlink()->mutable_loss() = parse_loss(f.loss, "--loss");
    if (!f.uplink_loss.empty()) {
      *job.mutable_uplink()->mutable_loss() = parse_loss(f.uplink_loss, "--uplink-loss");
    }
    if (!f.sample_period.empty()) {
      job.set_sample_period_s(parse_quantity(f.sample_period, Quantity::time, "--sample-period"));
      if (!(job.sample_period_s() > 0.0)) {
        throw std::invalid_argument("--sample-period: expected a positive duration such as 5ms");
      }
    }
    if (!f.duration.empty()) job.set_duration_s(parse_quantity(f.duration, Quantity::time, "--duration"));
    if (!f.deadline.empty()) job.set_deadline_s(parse_quantity(f.deadline, Quantity::time, "--deadline"));
    if (!f.compute_delay.empty()) {
      job.set_compute_delay_s(parse_quantity(f.compute_delay, Quantity::time, "--compute-delay"));
    }
    if (!f.divergence_limit.empty()) {
      job.set_divergence_limit_m(parse_quantity(f.divergence_limit, Quantity::length, "--divergence-limit"));
      if (!(job.divergence_limit_m() > 0.0)) {
        throw std::invalid_argument("--divergence-limit: expected a positive length such as 50mm");
      }
    }
    if (!f.contour_error_limit.empty()) {
      job.set_contour_error_limit_m(
          parse_quantity(f.contour_error_limit, Quantity::length, "--contour-error-limit"));
      if (!(job.contour_error_limit_m() > 0.0 && job.contour_error_limit_m() <= 1e3)) {
        throw std::invalid_argument("--contour-error-limit: expected a positive length such as 0.5mm");
      }
    }
    if (!f.command_limit.empty()) {
      job.set_command_limit(parse_quantity(f.command_limit, Quantity::plain, "--command-limit"));
      if (!(job.command_limit() > 0.0)) {
        throw std::invalid_argument("--command-limit: expected a positive number");
      }
    }
    if (!f.clock.empty()) job.set_clock(f.clock);
    if (!f.compensate.empty()) {
      if (const auto compensation = job::parse_compensation(f.compensate, "--compensate")) {
        *job.mutable_compensation() = *compensation;
      } else {
        job.clear_compensation();
      }
    }
    if (!f.axes.empty()) {
      try {
        job::rename_axes(job, split_list(f.axes));
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument(std::string("--") + error.what());
      }
    }
    if (f.iterations != 0) job.set_iterations(static_cast<std::uint32_t>(f.iterations));
    if (f.seed >= 0) job.set_seed(static_cast<std::uint64_t>(f.seed));
    const auto& registry = job::ControllerRegistry::global();
    const auto axes = job::axis_names(job);
    for (const auto& [group_name, text] : f.gains) {
      if (!text.empty()) job::parse_gain_flag(text, *registry.gain_group(group_name), axes, *job.mutable_controller());
    }
    if (!f.adrc_y.empty()) {
      if (axes.size() < 2) throw std::invalid_argument("--adrc-y: the job has no second axis");
      std::string entries;
      for (const auto& item : split_list(f.adrc_y)) entries += (entries.empty() ? "" : ",") + axes[1] + "." + item;
      job::parse_gain_flag(entries, *registry.gain_group("adrc"), axes, *job.mutable_controller());
    }
    if (!f.estimator.empty()) job.mutable_controller()->set_estimator(f.estimator);
    if (!f.initial_position.empty()) {
      *job.mutable_initial_position() = parse_position(f.initial_position, "--initial-position");
    }
    if (!f.sensor.empty()) {
      // resolution=..,noise=.. (lengths)
      for (const auto& item : split_list(f.sensor)) {
        const auto equals = item.find('=');
        const std::string key = item.substr(0, equals);
        if (equals == std::string::npos || (key != "resolution" && key != "noise")) {
          throw std::invalid_argument("--sensor: expected resolution=LENGTH,noise=LENGTH, got '" + item + "'");
        }
        const double value = parse_quantity(item.substr(equals + 1), Quantity::length, "--sensor " + key);
        if (key == "resolution") job.mutable_sensor()->set_resolution_m(value);
        if (key == "noise") job.mutable_sensor()->set_noise_stddev_m(value);
      }
    }
    job::apply_defaults(job);
  }
  // Delay trace files are read here, once, on this side: the jobs carry their samples, so a
  // server (which reads no file a client names) and netmc sim run the same spec.
  for (auto& job : plan.jobs) job::inline_delay_traces(job);
  if (!f.spec_file.empty()) {
    // Names (plant, controller, observer ...) are checked when the job is built: do it now so
    // the message names the file too.
    bool gains_given = !f.adrc_y.empty();
    for (const auto& [group, text] : f.gains) gains_given = gains_given || !text.empty();
    const bool overridden = changes_setup || !f.controllers.empty() || gains_given ||
                            !f.estimator.empty() || !f.deadline.empty() || !f.compute_delay.empty() ||
                            !f.command_limit.empty() || !f.divergence_limit.empty() ||
                            !f.contour_error_limit.empty() || !f.clock.empty() ||
                            !f.axes.empty() || !f.plant.empty() || !f.compensate.empty();
    for (const auto& job : plan.jobs) {
      try {
        job::build_contour_job(job, job::check_without_files());  // files are opened where the job runs
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument(f.spec_file + (overridden ? " (with the flags given): " : ": ") + error.what());
      }
    }
  }
  return plan;
}


void add_study_flags(CLI::App* app, StudyFlags& flags) {
  app->add_option("--clock", flags.clock,
                  "Distributed runs: lockstep (virtual time, equals sim) or realtime (wall clock)")
      ->check(CLI::IsMember({"lockstep", "realtime"}));
  app->add_option("--axes", flags.axes,
                  "Distributed runs: the axis names (netmc-axis --axes) that the contour's x, y (and z) "
                  "drive, e.g. stage1.x,stage1.y (default x,y; x,y,z for a contour in space)")
      ->type_name("X,Y");
  std::string presets;
  for (const auto& name : preset_names()) presets += (presets.empty() ? "" : ", ") + name;
  app->add_option("--preset", flags.preset, "Named study (default seed001, paper 001's Table 1): " + presets);
  app->add_option("--spec", flags.spec_file, "Job spec as JSON (protobuf JSON mapping of netmc.v1.JobSpec)");
  app->add_option("--trajectory", flags.trajectory, "circle:r=10mm,cx=50mm,cy=50mm,period=8s | ellipse:a=..,b=..,cx=..,cy=..,period=.. (or feed=..,amax=.. instead of period) | line:x0=..,y0=..,x1=..,y1=..,duration=.. | "
                  "lissajous:ax=20mm,ay=15mm,p=3,q=2,period=20s[,phase=..,cx=..,cy=..] (or feed=..,amax=.. instead of period) | "
                  "polyline:points=0,0;10mm,0;10mm,10mm,vmax=10mm/s,amax=100mm/s2[,corner=..] | "
                  "spline:points=X,Y;X,Y;...,feed=10mm/s,amax=50mm/s2[,at=..] (points closed when the last equals the first) | "
                  "one axis: multi-sine:terms=80mm/0.5/-1.5708;70mm/0.4/-1.5708,offset=150mm,duration=20s[,period=10s] "
                  "(amplitude/frequency in Hz/phase in rad; the error is x - x_d)");
  app->add_option("--controller", flags.controllers,
                  "NAME[,NAME...], each a run: " + job::ControllerRegistry::global().names_help());
  app->add_option("--delay", flags.delay, "Loop delay on the controller->actuator link: none | constant:1ms | uniform:min=0.3ms,max=0.8ms | normal:mean=..,sd=.. | pareto:scale=..,shape=.. | markov:good=A..B,bad=C..D,p_gb=..,p_bg=.. | trace:FILE.csv or trace:PING.txt[,rtt_share=0.5] (ping -D output: half of each round trip)");
  app->add_option("--seed", flags.seed, "Random seed")->check(CLI::NonNegativeNumber);
  add_job_override_flags(app, flags);
  app->add_option("--json", flags.json_path, "Write all iteration metrics as JSON");
  app->add_flag("--curve", flags.curve, "Print e_sum per iteration (the learning curve)");
}

void add_job_override_flags(CLI::App* app, StudyFlags& flags) {
  app->add_option("--plant", flags.plant,
                  "seed001 | ballscrew | linmotor | linmotor-flex | stage004 | hiwin, with parameter overrides for every axis or one: "
                  "ballscrew:load_kg=3 | ballscrew:y.load_kg=3,x.damping_n_m_s_rad=0.3 "
                  "(netmc sim --plant-parameters NAME lists the keys)")
      ->type_name("NAME[:[AXIS.]KEY=VALUE,...]");
  app->add_option("--disturbance", flags.disturbances,
                  "Additive disturbance on one axis in the plant's input unit (V, N or m/s^2), repeatable: "
                  "y:step=0.8,on=2.2s,off=5.2s | x:sine=0.2,hz=2[,phase=RAD] | x:noise=0.05,band=50[,seed=N] "
                  "| x:constant=0.1 (parts add up)")
      ->type_name("AXIS:PART=..,...");
  app->add_option("--dead-zone-inverse", flags.dead_zone_inverses,
                  "A fixed dead-zone inverse (thesis eq. 5-4) between the controller and one axis, repeatable: "
                  "x:b_r=0.3,b_l=-0.25[,m_r=0.9,m_l=1] (break points in V, slopes V/V; thesis 5.5: identify them "
                  "with a single-axis axis-diarc-dead-zone run)")
      ->type_name("AXIS:b_r=..,b_l=..,...");
  app->add_option("--uplink-delay", flags.uplink_delay, "Sensor->controller delay (same forms as --delay)");
  app->add_option("--loss", flags.loss, "Setpoint loss: none | bernoulli:p=0.01 | gilbert:p_gb=..,p_bg=..[,good=..,bad=..]");
  app->add_option("--uplink-loss", flags.uplink_loss, "Feedback loss (same forms as --loss)");
  app->add_option("--compensate", flags.compensate,
                  "Delay compensation: " + job::delay_compensator_syntax() +
                      " (netmc sim --list-compensators; default none, the loop as the papers run it; netmc sweep: "
                      "a list, one axis of the grid, e.g. none,predictor)");
  app->add_option("--sample-period", flags.sample_period, "Sample period h, e.g. 5ms");
  app->add_option("--duration", flags.duration, "Run length per iteration (default: the trajectory's)");
  app->add_option("--deadline", flags.deadline, "How long the server waits for feedback (default: one period)");
  app->add_option("--compute-delay", flags.compute_delay, "Computation delay tau_cc in virtual time");
  app->add_option("--divergence-limit", flags.divergence_limit, "Contour error at which a run counts as unstable and stops (default 50mm)");
  app->add_option("--contour-error-limit", flags.contour_error_limit,
                  "Contour error beyond which the job stops at once, naming the crossing: a realtime job fails with "
                  "its axes quick-stopped, a simulated run ends there as unstable (default: a quarter of the "
                  "reference's size for a realtime job, none otherwise)");
  app->add_option("--command-limit", flags.command_limit, "Command saturation |U| enforced at the axis (default: none)");
  app->add_option("--iterations", flags.iterations, "ILC iterations per run (1..100000)")->check(CLI::Range(1, 100000));
  // One flag per gains group of the controller registry: a new family's appears by itself.
  for (const auto& group : job::ControllerRegistry::global().gain_groups()) {
    app->add_option(group.flag, flags.gains[group.name], group.summary + ": " + group.syntax());
  }
  app->add_option("--adrc-y", flags.adrc_y, "The second axis's ADRC gains where they differ from --adrc (same keys; "
                                            "the same as --adrc AXIS.KEY=..)");
  app->add_option("--estimator", flags.estimator, "Contour-error estimator of a cross-coupled controller: curvature | tangent | newton | steffensen");
  app->add_option("--initial-position", flags.initial_position, "Where the axes rest at t = 0, x=..,y=.. (default: the trajectory's start)");
  app->add_option("--sensor", flags.sensor, "Position sensor: resolution=0.5um,noise=0.1um");
}

}  // namespace netmc::cli
