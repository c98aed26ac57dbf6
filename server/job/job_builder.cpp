#include "server/job/job_builder.hpp"

#include <fmt/format.h>
#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/trajectory/cubic_spline_curve.hpp"
#include "control/trajectory/ellipse_trajectory.hpp"
#include "control/trajectory/feed_rate_trajectory.hpp"
#include "control/trajectory/halted_trajectory.hpp"
#include "control/trajectory/heart_trajectory.hpp"
#include "control/trajectory/line_trajectory.hpp"
#include "control/trajectory/lissajous_trajectory.hpp"
#include "control/trajectory/polyline_trajectory.hpp"
#include "control/trajectory/multi_sine_reference.hpp"
#include "control/trajectory/spatial_circle.hpp"
#include "plant/plant_catalog.hpp"
#include "server/job/controller_registry.hpp"
#include "server/job/dead_zone_spec.hpp"
#include "server/job/delay_compensators.hpp"
#include "server/job/legacy_spec.hpp"
#include "server/job/plant_source.hpp"
#include "server/job/quantity_text.hpp"
#include "server/job/reference_limits.hpp"

namespace netmc::job {
namespace {

using netmc::v1::DelayProfile;
using netmc::v1::LossProfile;

// Points of a polyline or spline; the spline's construction solves a dense system in their count.
constexpr int kMaxContourPoints = 1000;

std::vector<Eigen::Vector2d> build_points(const google::protobuf::RepeatedPtrField<netmc::v1::Point2>& points) {
  if (points.size() > kMaxContourPoints) {
    throw std::invalid_argument("points: at most " + std::to_string(kMaxContourPoints) + ", got " +
                                std::to_string(points.size()));
  }
  std::vector<Eigen::Vector2d> out;
  out.reserve(static_cast<std::size_t>(points.size()));
  for (const auto& p : points) out.emplace_back(p.x_m(), p.y_m());
  return out;
}

control::FeedRateLimits build_feed(const netmc::v1::FeedRate& f) {
  control::FeedRateLimits limits;
  limits.feed_m_s = f.feed_m_s();
  limits.normal_acceleration_m_s2 = f.max_normal_acceleration_m_s2();
  limits.tangential_acceleration_m_s2 = f.max_tangential_acceleration_m_s2() == 0.0
                                            ? f.max_normal_acceleration_m_s2()
                                            : f.max_tangential_acceleration_m_s2();
  return limits;
}

std::shared_ptr<const control::ReferenceTrajectory> build_shape(const netmc::v1::Trajectory& t) {
  switch (t.shape_case()) {
    case netmc::v1::Trajectory::kCircle: {
      const auto& c = t.circle();
      control::CircleParameters p;
      p.center = {c.center_x_m(), c.center_y_m()};
      p.radius_m = c.radius_m();
      p.period_s = c.period_s();
      p.start_angle_rad = c.start_angle_rad();
      p.clockwise = c.clockwise();
      p.revolutions = c.revolutions() == 0.0 ? 1.0 : c.revolutions();
      p.ramp_s = c.ramp_s();
      return std::make_shared<control::CircleTrajectory>(p);
    }
    case netmc::v1::Trajectory::kEllipse: {
      const auto& e = t.ellipse();
      control::EllipseParameters p;
      p.center = {e.center_x_m(), e.center_y_m()};
      p.semi_axis_x_m = e.semi_axis_x_m();
      p.semi_axis_y_m = e.semi_axis_y_m();
      p.period_s = e.period_s();
      p.start_angle_rad = e.start_angle_rad();
      p.clockwise = e.clockwise();
      p.revolutions = e.revolutions() == 0.0 ? 1.0 : e.revolutions();
      if (e.has_feed()) {
        if (p.revolutions != 1.0) {
          throw std::invalid_argument("ellipse revolutions: a feed-rate ellipse runs one revolution, got " +
                                      std::to_string(p.revolutions));
        }
        p.period_s = 1.0;  // unused: the feed times the motion
        return std::make_shared<control::FeedRateTrajectory>(std::make_shared<control::EllipseCurve>(p),
                                                             build_feed(e.feed()));
      }
      return std::make_shared<control::EllipseTrajectory>(p);
    }
    case netmc::v1::Trajectory::kLine: {
      const auto& l = t.line();
      control::LineParameters p;
      p.start = {l.x0_m(), l.y0_m()};
      p.end = {l.x1_m(), l.y1_m()};
      p.duration_s = l.duration_s();
      return std::make_shared<control::LineTrajectory>(p);
    }
    case netmc::v1::Trajectory::kLissajous: {
      const auto& l = t.lissajous();
      control::LissajousParameters p;
      p.center = {l.center_x_m(), l.center_y_m()};
      p.amplitude_x_m = l.amplitude_x_m();
      p.amplitude_y_m = l.amplitude_y_m();
      if (l.frequency_x() > 1000 || l.frequency_y() > 1000) {
        throw std::invalid_argument("lissajous frequency_x, frequency_y: expected whole numbers in [1, 1000], got " +
                                    std::to_string(l.frequency_x()) + ", " + std::to_string(l.frequency_y()));
      }
      p.frequency_x = static_cast<int>(l.frequency_x());
      p.frequency_y = static_cast<int>(l.frequency_y());
      p.phase_rad = l.phase_rad();
      if (l.has_feed()) {
        return std::make_shared<control::FeedRateTrajectory>(std::make_shared<control::LissajousCurve>(p),
                                                             build_feed(l.feed()));
      }
      p.period_s = l.period_s();
      return std::make_shared<control::LissajousTrajectory>(p);
    }
    case netmc::v1::Trajectory::kPolyline: {
      const auto& l = t.polyline();
      control::PolylineParameters p;
      p.points = build_points(l.points());
      p.max_speed_m_s = l.max_speed_m_s();
      p.max_acceleration_m_s2 = l.max_acceleration_m_s2();
      p.corner_speed_m_s = l.corner_speed_m_s();
      p.max_jerk_m_s3 = l.max_jerk_m_s3();
      return std::make_shared<control::PolylineTrajectory>(p);
    }
    case netmc::v1::Trajectory::kSpline: {
      const auto& s = t.spline();
      auto curve = std::make_shared<control::CubicSplineCurve>(build_points(s.points()));
      return std::make_shared<control::FeedRateTrajectory>(std::move(curve), build_feed(s.feed()));
    }
    case netmc::v1::Trajectory::kHeart: {
      const auto& h = t.heart();
      control::HeartParameters p;
      p.center = {h.center_x_m(), h.center_y_m()};
      p.scale_m = h.scale_m();
      p.period_s = h.period_s();
      return std::make_shared<control::HeartTrajectory>(p);
    }
    case netmc::v1::Trajectory::kSpatialCircle:
      throw std::invalid_argument("trajectory.spatial_circle: a three-axis contour, not a planar trajectory");
    case netmc::v1::Trajectory::kMultiSine:
      throw std::invalid_argument("trajectory.multi_sine: a single-axis reference, not a planar trajectory");
    case netmc::v1::Trajectory::SHAPE_NOT_SET:
      break;
  }
  throw std::invalid_argument(
      "trajectory: missing (expected circle, ellipse, line, heart, lissajous, polyline or spline)");
}

std::shared_ptr<const control::ReferenceTrajectory> build_trajectory(
    const netmc::v1::Trajectory& t) {
  auto motion = build_shape(t);
  if (!t.has_halt()) return motion;
  return std::make_shared<control::HaltedTrajectory>(std::move(motion), t.halt().at_s(),
                                                     t.halt().duration_s());
}

std::shared_ptr<const control::SpatialCircle> build_spatial_circle(const netmc::v1::JobSpec& spec) {
  const auto& c = spec.trajectory().spatial_circle();
  if (spec.trajectory().has_halt()) {
    throw std::invalid_argument("trajectory.spatial_circle: a halt is planar only; expected none");
  }
  if (!(c.revolutions() >= 0.0) || !std::isfinite(c.revolutions()) || c.revolutions() > 1e6) {
    throw std::invalid_argument("trajectory.spatial_circle.revolutions: expected 0 (4) or a positive number up to 1e6");
  }
  control::SpatialCircleParameters p;
  p.center = Eigen::Vector3d(c.center_x_m(), c.center_y_m(), c.center_z_m());
  p.radius_m = c.radius_m();
  p.normal = Eigen::Vector3d(c.normal_x(), c.normal_y(), c.normal_z());
  p.start = Eigen::Vector3d(c.start_x(), c.start_y(), c.start_z());
  p.period_s = c.period_s();
  if (!p.center.allFinite() || !p.normal.allFinite() || !p.start.allFinite() || !std::isfinite(p.radius_m) ||
      !std::isfinite(p.period_s)) {
    throw std::invalid_argument("trajectory.spatial_circle: expected finite numbers");
  }
  try {
    return std::make_shared<control::SpatialCircle>(p);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(std::string("trajectory.spatial_circle: ") + error.what());
  }
}

std::shared_ptr<const control::MultiSineReference> build_axis_reference(const netmc::v1::JobSpec& spec) {
  const auto& m = spec.trajectory().multi_sine();
  if (spec.trajectory().has_halt()) {
    throw std::invalid_argument("trajectory.multi_sine: a halt is planar only; expected none");
  }
  if (m.terms_size() > static_cast<int>(control::MultiSineReference::kMaxTerms)) {
    throw std::invalid_argument("trajectory.multi_sine.terms: expected 1 to 16 sinusoids, got " +
                                std::to_string(m.terms_size()));
  }
  control::MultiSineParameters p;
  p.offset_m = m.offset_m();
  for (const auto& term : m.terms()) p.terms.push_back({term.amplitude_m(), term.frequency_hz(), term.phase_rad()});
  p.duration_s = m.duration_s();
  p.period_s = m.period_s() != 0.0 ? m.period_s() : m.duration_s();
  return std::make_shared<control::MultiSineReference>(p);  // its messages name the field
}

// A trace of ping output: the share of each round trip taken as one delay (unset: a half).
double round_trip_share(const netmc::v1::TraceDelay& trace) {
  return trace.round_trip_share() != 0.0 ? trace.round_trip_share() : 0.5;
}

std::unique_ptr<netsim::DelayModel> build_delay(const DelayProfile& d) {
  switch (d.kind_case()) {
    case DelayProfile::KIND_NOT_SET:
    case DelayProfile::kNone:
      return netsim::make_no_delay();
    case DelayProfile::kConstantS:
      return netsim::make_constant_delay(d.constant_s());
    case DelayProfile::kUniform:
      return netsim::make_uniform_delay(d.uniform().min_s(), d.uniform().max_s());
    case DelayProfile::kNormal: {
      const auto& n = d.normal();
      const double max_s = n.max_s() > 0.0 ? n.max_s() : n.mean_s() + 6.0 * n.stddev_s();
      return netsim::make_truncated_normal_delay(n.mean_s(), n.stddev_s(), n.min_s(), max_s);
    }
    case DelayProfile::kPareto: {
      const auto& p = d.pareto();
      const double max_s = p.max_s() > 0.0 ? p.max_s() : std::numeric_limits<double>::infinity();
      return netsim::make_pareto_delay(p.scale_s(), p.shape(), max_s);
    }
    case DelayProfile::kMarkov: {
      const auto& m = d.markov();
      return netsim::make_markov_delay(
          netsim::make_uniform_delay(m.good().min_s(), m.good().max_s()),
          netsim::make_uniform_delay(m.bad().min_s(), m.bad().max_s()), m.p_good_to_bad(),
          m.p_bad_to_good());
    }
    case DelayProfile::kTrace: {
      const auto& t = d.trace();
      if (t.delays_s_size() > 0) {
        return netsim::make_trace_delay({t.delays_s().begin(), t.delays_s().end()});
      }
      if (t.path().empty()) {
        throw std::invalid_argument("delay trace: expected a CSV file path or delays_s values");
      }
      return netsim::make_trace_delay(netsim::load_delay_trace(t.path(), round_trip_share(t)));
    }
  }
  throw std::invalid_argument("delay: unknown kind");
}

std::unique_ptr<netsim::LossModel> build_loss(const LossProfile& l) {
  switch (l.kind_case()) {
    case LossProfile::KIND_NOT_SET:
      return netsim::make_no_loss();
    case LossProfile::kBernoulli:
      return netsim::make_bernoulli_loss(l.bernoulli().p());
    case LossProfile::kGilbertElliott: {
      const auto& g = l.gilbert_elliott();
      return netsim::make_gilbert_elliott_loss(g.p_good_to_bad(), g.p_bad_to_good(),
                                               g.loss_in_good(), g.loss_in_bad());
    }
  }
  throw std::invalid_argument("loss: unknown kind");
}

// Prefix the field path onto errors thrown by the libraries.
template <typename Build>
auto in_field(const std::string& field, Build&& build) {
  try {
    return build();
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    if (message.rfind(field + ":", 0) == 0 || message.rfind(field + ".", 0) == 0) throw;  // named already
    throw std::invalid_argument(field + ": " + message);
  }
}

sim::LinkProfile build_link(const netmc::v1::LinkProfile& link, const std::string& field) {
  sim::LinkProfile out;
  out.delay = in_field(field + ".delay", [&] { return build_delay(link.delay()); });
  out.loss = in_field(field + ".loss", [&] { return build_loss(link.loss()); });
  return out;
}

// controller.dead_zone_inverse by axis name, in the group's order (none: no gap, slope 1).
std::vector<control::DeadZoneEstimate> build_dead_zone_inverse(const netmc::v1::JobSpec& spec) {
  const auto& entries = spec.controller().dead_zone_inverse();
  if (entries.empty()) return {};
  const auto names = axis_names(spec);
  std::vector<control::DeadZoneEstimate> out(names.size());
  std::vector<bool> seen(names.size(), false);
  for (int i = 0; i < entries.size(); ++i) {
    const std::string field = "controller.dead_zone_inverse[" + std::to_string(i) + "]";
    const auto it = std::find(names.begin(), names.end(), entries[i].axis());
    if (it == names.end()) {
      throw std::invalid_argument(field + ".axis: expected an axis of the job, got '" + entries[i].axis().substr(0, 64) + "'");
    }
    const auto index = static_cast<std::size_t>(it - names.begin());
    if (seen[index]) throw std::invalid_argument(field + ".axis: axis '" + entries[i].axis() + "' is given twice");
    seen[index] = true;
    out[index] = build_dead_zone(entries[i].dead_zone(), field + ".dead_zone");
  }
  return out;
}

// spec.plant_axes as the plant catalog's per-axis overrides, in the group's axis order.
std::vector<plant::AxisOverrides> build_plant_overrides(const netmc::v1::JobSpec& spec, std::size_t axis_count) {
  constexpr int kMaxParameters = 32;
  const auto names = axis_names(spec);
  std::vector<plant::AxisOverrides> out(axis_count);
  std::vector<bool> seen(axis_count, false);
  for (int i = 0; i < spec.plant_axes_size(); ++i) {
    const auto& a = spec.plant_axes(i);
    const std::string field = "plant_axes[" + std::to_string(i) + "]";
    const auto it = std::find(names.begin(), names.end(), a.axis());
    if (it == names.end()) {
      throw std::invalid_argument(field + ".axis: expected an axis of the job, got '" + a.axis().substr(0, 64) + "'");
    }
    const auto index = static_cast<std::size_t>(it - names.begin());
    if (seen[index]) throw std::invalid_argument(field + ".axis: axis '" + a.axis() + "' is given twice");
    seen[index] = true;
    if (a.parameters_size() > kMaxParameters) {
      throw std::invalid_argument(field + ".parameters: expected at most " + std::to_string(kMaxParameters));
    }
    for (const auto& p : a.parameters()) out[index].parameters.emplace_back(p.key(), p.value());
    const auto& d = a.disturbance();
    plant::Disturbance& disturbance = out[index].disturbance;
    disturbance.constant = d.constant();
    disturbance.step_amplitude = d.step().amplitude();
    disturbance.step_time_s = d.step().on_s();
    if (d.step().off_s() != 0.0) disturbance.step_off_s = d.step().off_s();
    disturbance.sine_amplitude = d.sine().amplitude();
    disturbance.sine_frequency_hz = d.sine().frequency_hz();
    disturbance.sine_phase_rad = d.sine().phase_rad();
    if (d.noise().stddev() != 0.0) {
      if (!(d.noise().bandwidth_hz() > 0.0 && d.noise().bandwidth_hz() <= 1e5)) {
        throw std::invalid_argument(field + ".disturbance.noise.bandwidth_hz: expected a number in (0, 1e5] Hz");
      }
      const std::uint64_t seed = d.noise().seed() != 0 ? d.noise().seed() : spec.seed() * 1000003ULL + index + 1;
      disturbance.noise = plant::make_band_limited_noise(d.noise().stddev(), d.noise().bandwidth_hz(), seed);
    }
    plant::validate_disturbance(disturbance, field);
  }
  return out;
}

// " (y: load_kg=3, disturbance)" for the axes a spec changes; empty when it changes none.
std::string describe_plant_axes(const netmc::v1::JobSpec& spec) {
  std::string out;
  for (const auto& a : spec.plant_axes()) {
    std::string parts;
    for (const auto& p : a.parameters()) parts += (parts.empty() ? "" : ", ") + p.key() + "=" + fmt::format("{:g}", p.value());
    if (a.has_disturbance()) parts += std::string(parts.empty() ? "" : ", ") + "disturbance";
    if (!parts.empty()) out += (out.empty() ? "" : "; ") + a.axis() + ": " + parts;
  }
  return out.empty() ? out : " (" + out + ")";
}

std::string format_seconds(double seconds) {
  std::ostringstream text;
  if (seconds >= 1.0 || seconds == 0.0) {
    text << seconds << " s";
  } else if (seconds >= 1e-3) {
    text << seconds * 1e3 << " ms";
  } else {
    text << seconds * 1e6 << " us";
  }
  return text.str();
}

}  // namespace

void check_name(const std::string& name, const std::string& field) {
  const bool valid = !name.empty() && name.size() <= 64 &&
                     std::all_of(name.begin(), name.end(), [](char c) {
                       return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                              c == '_' || c == '.' || c == '-';
                     });
  if (!valid) {
    throw std::invalid_argument(field + ": expected a name of 1-64 characters A-Z a-z 0-9 _ . -, got '" +
                                name.substr(0, 80) + "'");
  }
}

std::size_t plant_axis_index(const std::vector<std::string>& axis_names, std::size_t axis) {
  if (axis_names.size() != 1) return axis;
  return axis_names.front() == "y" ? 1 : axis_names.front() == "z" ? 2 : 0;
}

std::vector<std::string> axis_names(const netmc::v1::JobSpec& spec) {
  const std::size_t count = group_axis_count(spec);
  if (spec.axes_size() == 0) {
    const std::vector<std::string> defaults{"x", "y", "z"};
    return {defaults.begin(), defaults.begin() + static_cast<std::ptrdiff_t>(count)};
  }
  if (static_cast<std::size_t>(spec.axes_size()) != count) {
    // One axis named for a law of a group: say which laws run one axis, and how.
    const std::string single_axis =
        spec.axes_size() == 1 && count > 1
            ? "; a single axis runs a single-axis law on a multi-sine reference (" +
                  join_list(ControllerRegistry::global().single_axis_names()) +
                  "), e.g. --axes " + spec.axes(0).substr(0, 32) + " --preset thesis-dead-zone --controller axis-diarc"
            : "";
    throw std::invalid_argument("axes: a " + std::to_string(count) + "-axis job needs " + std::to_string(count) +
                                (count == 1 ? " axis name, got " : " axis names, got ") + std::to_string(spec.axes_size()) +
                                single_axis);
  }
  std::vector<std::string> names(spec.axes().begin(), spec.axes().end());
  for (std::size_t i = 0; i < names.size(); ++i) {
    check_name(names[i], "axes");
    for (std::size_t j = 0; j < i; ++j) {
      if (names[i] == names[j]) throw std::invalid_argument("axes: the axis names must differ, got '" + names[i] + "' twice");
    }
  }
  return names;
}

void rename_axes(netmc::v1::JobSpec& spec, const std::vector<std::string>& names) {
  const auto old_names = axis_names(spec);
  netmc::v1::JobSpec renamed = spec;
  renamed.clear_axes();
  for (const auto& name : names) renamed.add_axes(name);
  axis_names(renamed);  // checks count, form and uniqueness
  // What names an axis keeps naming the same axis, by its place in the group.
  const auto rename = [&](std::string& axis) {
    for (std::size_t i = 0; i < old_names.size(); ++i) {
      if (axis == old_names[i]) {
        axis = names[i];
        return;
      }
    }
  };
  for (auto& settings : *renamed.mutable_plant_axes()) rename(*settings.mutable_axis());
  for (auto& inverse : *renamed.mutable_controller()->mutable_dead_zone_inverse()) rename(*inverse.mutable_axis());
  for (auto& [group, gains] : *renamed.mutable_controller()->mutable_gains()) {
    google::protobuf::Map<std::string, netmc::v1::AxisGains> axes;
    for (const auto& [axis, own] : gains.axes()) {
      std::string name = axis;
      rename(name);
      axes[name] = own;
    }
    *gains.mutable_axes() = axes;
  }
  spec = std::move(renamed);
}

void apply_defaults(netmc::v1::JobSpec& spec) {
  if (spec.plant().empty()) spec.set_plant("seed001");
  if (spec.controller().name().empty()) spec.mutable_controller()->set_name("adrc+ilccc");
  if (spec.sample_period_s() == 0.0) spec.set_sample_period_s(0.005);
  if (spec.iterations() == 0) spec.set_iterations(1);
  if (spec.seed() == 0) spec.set_seed(1);
}

namespace {

// The documented ranges of a spec's scalar fields (docs/operations/hostile-networks-and-clients.md, "Job spec limits"), checked before
// anything is built, so an absurd spec costs nothing.
void check_ranges(const netmc::v1::JobSpec& spec) {
  const auto require = [](double value, double low, double high, const std::string& field, const std::string& unit) {
    if (!(value >= low && value <= high)) {
      throw std::invalid_argument(field + ": expected a number in [" + fmt::format("{:g}", low) + ", " +
                                  fmt::format("{:g}", high) + "]" + unit + ", got " + fmt::format("{:g}", value));
    }
  };
  if (spec.name().size() > kMaxJobNameBytes) {
    throw std::invalid_argument("name: expected at most " + std::to_string(kMaxJobNameBytes) + " bytes, got " +
                                std::to_string(spec.name().size()));
  }
  if (spec.sample_period_s() != 0.0) require(spec.sample_period_s(), 1e-6, 1.0, "sample_period", " s");
  if (spec.iterations() > kMaxIterations) {
    throw std::invalid_argument("iterations: expected at most " + std::to_string(kMaxIterations) + ", got " +
                                std::to_string(spec.iterations()));
  }
  require(spec.duration_s(), 0.0, 1e6, "duration", " s");
  require(spec.deadline_s(), 0.0, 60.0, "deadline", " s");
  require(spec.compute_delay_s(), 0.0, 60.0, "compute_delay", " s");
  require(spec.evaluation_start_s(), 0.0, 1e6, "evaluation_start", " s");
  require(spec.command_limit(), 0.0, 1e6, "command_limit", " (0: none)");
  require(spec.divergence_limit_m(), 0.0, 1e3, "divergence_limit", " m (0: 50 mm)");
  if (spec.has_contour_error_limit_m() &&
      !(spec.contour_error_limit_m() > 0.0 && spec.contour_error_limit_m() <= 1e3)) {
    throw std::invalid_argument("contour_error_limit_m: expected a length in (0, 1000] m");
  }
  require(spec.sensor().resolution_m(), 0.0, 1.0, "sensor.resolution", " m");
  require(spec.sensor().noise_stddev_m(), 0.0, 1.0, "sensor.noise_stddev", " m");
  if (spec.has_initial_position()) {
    require(spec.initial_position().x_m(), -kWorkspaceM, kWorkspaceM, "initial_position.x", " m");
    require(spec.initial_position().y_m(), -kWorkspaceM, kWorkspaceM, "initial_position.y", " m");
  }
  check_reference_limits(spec.trajectory(), spec.sample_period_s());
}

}  // namespace

void reject_file_references(const netmc::v1::JobSpec& spec) {
  for (const auto& [link, field] : {std::pair{&spec.uplink(), "uplink"}, std::pair{&spec.downlink(), "downlink"}}) {
    if (link->delay().has_trace() && !link->delay().trace().path().empty()) {
      throw std::invalid_argument(std::string(field) +
                                  ".delay.trace.path: a job from the network names no file (this side reads "
                                  "none); send the delays inline in delays_s (netmc run does)");
    }
  }
}

void inline_delay_traces(netmc::v1::JobSpec& spec) {
  for (auto* link : {spec.mutable_uplink(), spec.mutable_downlink()}) {
    auto& delay = *link->mutable_delay();
    if (!delay.has_trace() || delay.trace().path().empty()) continue;
    if (delay.trace().delays_s_size() == 0) {
      for (const double value : netsim::load_delay_trace(delay.trace().path(), round_trip_share(delay.trace()))) {
        delay.mutable_trace()->add_delays_s(value);
      }
    }
    delay.mutable_trace()->clear_path();
    delay.mutable_trace()->clear_round_trip_share();  // applied: the delays are one-way
  }
}

sim::ContourJob build_contour_job(const netmc::v1::JobSpec& spec, const JobBuildOptions& options) {
  check_ranges(spec);
  sim::ContourJob job;
  if (is_spatial_job(spec)) {
    job.reference = in_field("trajectory", [&] { return build_spatial_circle(spec); });
    const auto& c = spec.trajectory().spatial_circle();
    job.duration_s = spec.duration_s() > 0.0 ? spec.duration_s() : (c.revolutions() > 0.0 ? c.revolutions() : 4.0) * c.period_s();
  } else if (is_single_axis_job(spec)) {
    job.reference = in_field("trajectory", [&] { return build_axis_reference(spec); });
    job.duration_s = spec.duration_s();
  } else {
    job.reference = in_field("trajectory", [&] { return build_trajectory(spec.trajectory()); });
    job.duration_s = spec.duration_s();
  }
  job.axis_names = in_field("axes", [&] { return axis_names(spec); });
  const bool single_axis = job.axis_count() == 1;
  job.plant_name = spec.plant();
  const auto overrides = build_plant_overrides(spec, job.axis_count());
  if (!options.load_plant_files && is_file_plant(spec.plant())) {
    auto plants = remote_plant_set(spec.plant(), job.axis_count());
    for (auto& axis : plants.axes) job.axes.emplace_back(std::move(axis));
  } else if (single_axis) {
    // One axis of a stage, with that axis's parameters.
    const std::size_t index = plant_axis_index(job.axis_names, 0);
    std::vector<plant::AxisOverrides> placed(index + 1);
    if (!overrides.empty()) placed[index] = overrides.front();
    auto plants = in_field("plant", [&] { return make_job_plant_set(spec.plant(), index + 1, placed); });
    job.axes.emplace_back(std::move(plants.axes[index]));
  } else {
    auto plants = in_field("plant", [&] { return make_job_plant_set(spec.plant(), job.axis_count(), overrides); });
    for (auto& axis : plants.axes) job.axes.emplace_back(std::move(axis));
  }
  job.controller_name = spec.controller().name();
  job.dead_zone_inverse = build_dead_zone_inverse(spec);
  // The controller is resolved and built once here, so that a bad name or gain is reported
  // before anything runs.
  job.controller_factory = ControllerRegistry::global().resolve(spec.controller(), job.reference, job.axis_names,
                                                                spec.sample_period_s(), options.controller_plugins);
  job.compensation = build_compensation(spec, job.reference, job.axis_names);
  if (job.compensation && job.compensation->horizon > 1 && !job.make_controller()->clone()) {
    throw std::invalid_argument("compensation: " + compensation_text(spec.compensation()) + " runs the law ahead on a "
                                "copy of it, and controller '" + spec.controller().name().substr(0, 80) +
                                "' cannot be copied (those that can: contouring controllers of axis laws and "
                                "contour compensators, e.g. adrc, adrc+pidccc, adrc+ilccc)");
  }
  job.uplink = build_link(spec.uplink(), "uplink");
  job.downlink = build_link(spec.downlink(), "downlink");
  job.sensor.resolution_m = spec.sensor().resolution_m();
  job.sensor.noise_stddev_m = spec.sensor().noise_stddev_m();
  in_field("axes", [&] { return axis_names(spec); });
  if (!spec.clock().empty() && spec.clock() != "lockstep" && spec.clock() != "realtime") {
    throw std::invalid_argument("clock: expected 'lockstep' or 'realtime', got '" + spec.clock() + "'");
  }
  job.sample_period_s = spec.sample_period_s();
  job.iterations = spec.iterations();
  job.seed = spec.seed();
  job.deadline_s = spec.deadline_s();
  job.compute_delay_s = spec.compute_delay_s();
  if (!(spec.evaluation_start_s() >= 0.0)) {
    throw std::invalid_argument("evaluation_start: expected a non-negative duration");
  }
  job.evaluation_start_s = spec.evaluation_start_s();
  if (spec.command_limit() != 0.0) job.command_limit = spec.command_limit();
  if (spec.divergence_limit_m() != 0.0) job.divergence_limit_m = spec.divergence_limit_m();
  if (spec.has_contour_error_limit_m()) {
    job.contour_error_limit_m = spec.contour_error_limit_m();
  } else if (spec.clock() == "realtime") {
    job.contour_error_limit_m = kRealtimeContourErrorLimitShare * job.reference_size_m();
  }
  if (spec.has_initial_position()) {
    if (job.axis_count() == 3) {
      throw std::invalid_argument("initial_position: a three-axis contour starts on the contour; expected none");
    }
    if (single_axis) {
      throw std::invalid_argument("initial_position: a single-axis job starts at its reference's start; expected none");
    }
    job.initial_position = Eigen::Vector2d(spec.initial_position().x_m(), spec.initial_position().y_m());
  }
  job.validate();
  return job;
}

bool is_spatial_job(const netmc::v1::JobSpec& spec) { return spec.trajectory().has_spatial_circle(); }

bool is_single_axis_job(const netmc::v1::JobSpec& spec) { return spec.trajectory().has_multi_sine(); }

std::size_t group_axis_count(const netmc::v1::JobSpec& spec) {
  return is_spatial_job(spec) ? 3 : is_single_axis_job(spec) ? 1 : 2;
}

std::string describe_trajectory(const netmc::v1::Trajectory& trajectory) {
  if (trajectory.has_spatial_circle()) {
    const auto& c = trajectory.spatial_circle();
    return fmt::format("spatial circle(r={:g} mm, centre=({:g}, {:g}, {:g}) mm, normal=({:g}, {:g}, {:g}), period={:g} s)",
                       c.radius_m() * 1e3, c.center_x_m() * 1e3, c.center_y_m() * 1e3, c.center_z_m() * 1e3,
                       c.normal_x(), c.normal_y(), c.normal_z(), c.period_s());
  }
  if (trajectory.has_multi_sine()) {
    netmc::v1::JobSpec spec;
    *spec.mutable_trajectory() = trajectory;
    return build_axis_reference(spec)->describe();
  }
  return build_trajectory(trajectory)->describe();
}

std::string describe_link(const netmc::v1::LinkProfile& link) {
  const auto& d = link.delay();
  std::string text;
  switch (d.kind_case()) {
    case DelayProfile::KIND_NOT_SET:
    case DelayProfile::kNone: text = "none"; break;
    case DelayProfile::kConstantS: text = "constant " + format_seconds(d.constant_s()); break;
    case DelayProfile::kUniform:
      text = "uniform " + format_seconds(d.uniform().min_s()) + ".." +
             format_seconds(d.uniform().max_s());
      break;
    case DelayProfile::kNormal:
      text = "normal mean " + format_seconds(d.normal().mean_s()) + " sd " +
             format_seconds(d.normal().stddev_s());
      break;
    case DelayProfile::kPareto:
      text = "pareto scale " + format_seconds(d.pareto().scale_s()) + " shape " +
             std::to_string(d.pareto().shape());
      break;
    case DelayProfile::kMarkov:
      text = "markov good " + format_seconds(d.markov().good().max_s()) + " bad " +
             format_seconds(d.markov().bad().max_s());
      break;
    case DelayProfile::kTrace:
      // The same text whether the samples came from a file or inline (netmc run sends them inline).
      text = d.trace().path().empty() ? "trace of " + std::to_string(d.trace().delays_s_size()) + " samples"
                                      : "trace " + d.trace().path();
      break;
  }
  if (link.loss().kind_case() == LossProfile::kBernoulli) {
    text += ", loss " + std::to_string(link.loss().bernoulli().p());
  } else if (link.loss().kind_case() == LossProfile::kGilbertElliott) {
    text += ", bursty loss";
  }
  return text;
}

netmc::v1::IterationMetrics to_proto(const sim::IterationMetrics& m) {
  netmc::v1::IterationMetrics out;
  out.set_iteration(static_cast<std::uint32_t>(m.iteration));
  out.set_e_max_m(m.e_max_m);
  out.set_e_rms_m(m.e_rms_m);
  out.set_e_sum_m(m.e_sum_m);
  if (m.steady_samples > 0) {
    out.set_e_rms_steady_m(m.e_rms_steady_m);
    out.set_e_max_steady_m(m.e_max_steady_m);
  }
  out.set_tau_mean_s(m.tau_mean_s);
  out.set_tau_p50_s(m.tau_p50_s);
  out.set_tau_p99_s(m.tau_p99_s);
  out.set_tau_max_s(m.tau_max_s);
  out.set_tau_sc_mean_s(m.tau_sc_mean_s);
  out.set_tau_sc_p99_s(m.tau_sc_p99_s);
  out.set_tau_sc_max_s(m.tau_sc_max_s);
  out.set_tau_cc_mean_s(m.tau_cc_mean_s);
  out.set_tau_cc_p99_s(m.tau_cc_p99_s);
  out.set_tau_cc_max_s(m.tau_cc_max_s);
  out.set_tau_ca_mean_s(m.tau_ca_mean_s);
  out.set_tau_ca_p99_s(m.tau_ca_p99_s);
  out.set_tau_ca_max_s(m.tau_ca_max_s);
  for (const double v : m.tracking_rms_m) out.add_tracking_rms_m(v);
  for (const double v : m.tracking_max_m) out.add_tracking_max_m(v);
  for (const double v : m.command_rms) out.add_command_rms(v);
  if (m.steady_samples > 0) {
    for (const double v : m.command_rms_steady) out.add_command_rms_steady(v);
  }
  out.set_deadline_misses(static_cast<std::uint32_t>(m.deadline_misses));
  out.set_lost_feedback(static_cast<std::uint32_t>(m.lost_feedback));
  out.set_late_feedback(static_cast<std::uint32_t>(m.late_feedback));
  for (std::size_t i = 0; i < m.estimate_names.size() && i < m.final_estimates.size(); ++i) {
    auto& estimate = *out.add_estimates();
    estimate.set_name(m.estimate_names[i].name);
    estimate.set_unit(m.estimate_names[i].unit);
    estimate.set_value(m.final_estimates[i]);
  }
  out.set_lost_setpoints(static_cast<std::uint32_t>(m.lost_setpoints));
  out.set_stale_setpoints(static_cast<std::uint32_t>(m.stale_setpoints));
  out.set_diverged(m.diverged);
  out.set_diverged_at_s(m.diverged_at_s);
  if (!m.stop_reason.empty()) out.set_stop_reason(m.stop_reason);
  if (m.did_not_follow) out.set_did_not_follow(true);
  out.set_clock_uncertainty_s(m.clock_uncertainty_s);
  if (m.compensated) {
    out.set_feedback_age_mean_s(m.feedback_age_mean_s);
    out.set_feedback_age_p99_s(m.feedback_age_p99_s);
    out.set_feedback_age_max_s(m.feedback_age_max_s);
  }
  if (m.packets) {
    out.set_horizon_cycles(static_cast<std::uint32_t>(m.horizon_cycles));
    out.set_held_cycles(static_cast<std::uint32_t>(m.held_cycles));
  }
  return out;
}

netmc::v1::RunResult describe_run(const netmc::v1::JobSpec& spec,
                                  const std::string& controller_detail) {
  netmc::v1::RunResult result;
  result.set_controller(spec.controller().name());
  result.set_label(spec.name().empty() ? spec.controller().name() : spec.name());
  result.set_plant(spec.plant() + describe_plant_axes(spec));
  // The reference is built once: for its description and the period the window is counted in.
  double reference_period_s = 0.0;
  if (is_spatial_job(spec)) {
    result.set_trajectory(describe_trajectory(spec.trajectory()));
    reference_period_s = spec.trajectory().spatial_circle().period_s();
  } else if (is_single_axis_job(spec)) {
    const auto reference = build_axis_reference(spec);
    result.set_trajectory(reference->describe());
    reference_period_s = reference->period_s();
  } else {
    const auto trajectory = build_trajectory(spec.trajectory());
    result.set_trajectory(trajectory->describe());
    reference_period_s = trajectory->period_s();
  }
  std::string delay = describe_link(spec.downlink());
  if (spec.uplink().has_delay() || spec.uplink().has_loss()) {
    delay = "up: " + describe_link(spec.uplink()) + "; down: " + delay;
  }
  result.set_delay(delay);
  result.set_controller_detail(controller_detail);
  result.set_sample_period_s(spec.sample_period_s());
  result.set_seed(spec.seed());
  result.set_evaluation_start_s(sim::resolve_evaluation_start(spec.evaluation_start_s(), reference_period_s));
  if (spec.has_compensation()) result.set_compensation(compensation_text(spec.compensation()));
  return result;
}

netmc::v1::JobSpec parse_job_spec_json(const std::string& json, const std::string& origin) {
  netmc::v1::JobSpec spec;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status = google::protobuf::util::JsonStringToMessage(upgrade_legacy_spec_json(json), &spec, options);
  if (!status.ok()) {
    throw std::invalid_argument(origin + ": not a valid job spec: " +
                                std::string(status.message()));
  }
  return spec;
}

std::string to_json(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.add_whitespace = true;
  options.always_print_primitive_fields = true;
  std::string json;
  const auto status = google::protobuf::util::MessageToJsonString(message, &json, options);
  if (!status.ok()) throw std::runtime_error("json: " + std::string(status.message()));
  return json;
}

std::optional<double> delay_profile_bound_s(const netmc::v1::DelayProfile& d) {
  using netmc::v1::DelayProfile;
  switch (d.kind_case()) {
    case DelayProfile::KIND_NOT_SET:
    case DelayProfile::kNone: return 0.0;
    case DelayProfile::kConstantS: return d.constant_s();
    case DelayProfile::kUniform: return d.uniform().max_s();
    case DelayProfile::kNormal: return d.normal().max_s() > 0.0 ? std::optional<double>(d.normal().max_s()) : std::nullopt;
    case DelayProfile::kPareto: return d.pareto().max_s() > 0.0 ? std::optional<double>(d.pareto().max_s()) : std::nullopt;
    case DelayProfile::kMarkov: return std::max(d.markov().good().max_s(), d.markov().bad().max_s());
    case DelayProfile::kTrace:
      if (d.trace().delays_s().empty()) return std::nullopt;
      return *std::max_element(d.trace().delays_s().begin(), d.trace().delays_s().end());
  }
  return std::nullopt;
}

}  // namespace netmc::job
