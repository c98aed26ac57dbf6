#include "client/spec_syntax.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <vector>

#include "server/job/job_builder.hpp"
#include "server/job/plant_source.hpp"

namespace netmc::cli {
namespace {

using job::parse_keys;
using job::trim;

[[noreturn]] void fail(std::string_view field, const std::string& message) {
  throw std::invalid_argument(std::string(field) + ": " + message);
}

struct KindSpec {
  std::string kind;
  std::string argument;                     // text after ':'
  std::map<std::string, std::string> keys;  // when the argument is key=value,...
};

KindSpec split_kind(std::string_view text) {
  KindSpec spec;
  const std::size_t colon = text.find(':');
  spec.kind = std::string(trim(text.substr(0, colon)));
  if (colon != std::string_view::npos) spec.argument = std::string(trim(text.substr(colon + 1)));
  return spec;
}

double key_quantity(const std::map<std::string, std::string>& keys, const std::string& key,
                    Quantity quantity, std::string_view field, std::optional<double> fallback = {}) {
  const auto it = keys.find(key);
  if (it == keys.end()) {
    if (fallback) return *fallback;
    fail(field, "missing key '" + key + "'");
  }
  return parse_quantity(it->second, quantity, std::string(field) + " " + key);
}

// "X,Y;X,Y;..." -> points, each coordinate a length.
google::protobuf::RepeatedPtrField<netmc::v1::Point2> parse_points(const std::map<std::string, std::string>& keys,
                                                                   std::string_view field) {
  const auto it = keys.find("points");
  if (it == keys.end()) fail(field, "missing key 'points' (expected points=X,Y;X,Y;... such as 0,0;10mm,0;10mm,10mm)");
  google::protobuf::RepeatedPtrField<netmc::v1::Point2> points;
  std::string_view text = it->second;
  int index = 0;
  while (true) {
    ++index;
    const std::size_t semicolon = text.find(';');
    const std::string_view item = trim(text.substr(0, semicolon));
    const std::size_t comma = item.find(',');
    const std::string name = std::string(field) + " points: point " + std::to_string(index);
    if (comma == std::string_view::npos || item.find(',', comma + 1) != std::string_view::npos) {
      fail(name, "expected X,Y (two lengths such as 10mm,0), got '" + std::string(item) + "'");
    }
    auto& point = *points.Add();
    point.set_x_m(parse_quantity(item.substr(0, comma), Quantity::length, name + " x"));
    point.set_y_m(parse_quantity(item.substr(comma + 1), Quantity::length, name + " y"));
    if (semicolon == std::string_view::npos) break;
    text.remove_prefix(semicolon + 1);
  }
  return points;
}

// terms=A/F/P;A/F/P;..: amplitude (a length), frequency (Hz), phase (rad).
google::protobuf::RepeatedPtrField<netmc::v1::SineTerm> parse_sine_terms(
    const std::map<std::string, std::string>& keys, std::string_view field) {
  const auto it = keys.find("terms");
  if (it == keys.end()) {
    fail(field, "missing key 'terms' (expected terms=A/F/P;A/F/P;... such as 80mm/0.5/-1.5708)");
  }
  google::protobuf::RepeatedPtrField<netmc::v1::SineTerm> terms;
  std::string_view text = it->second;
  for (int index = 1; index <= 17; ++index) {
    const std::size_t semicolon = text.find(';');
    const std::string_view item = trim(text.substr(0, semicolon));
    const std::string name = std::string(field) + " terms: term " + std::to_string(index);
    const std::size_t first = item.find('/');
    const std::size_t second = first == std::string_view::npos ? first : item.find('/', first + 1);
    if (second == std::string_view::npos || item.find('/', second + 1) != std::string_view::npos) {
      fail(name, "expected AMPLITUDE/FREQUENCY_HZ/PHASE_RAD such as 80mm/0.5/-1.5708, got '" + std::string(item) + "'");
    }
    auto& term = *terms.Add();
    term.set_amplitude_m(parse_quantity(item.substr(0, first), Quantity::length, name + " amplitude"));
    term.set_frequency_hz(parse_quantity(item.substr(first + 1, second - first - 1), Quantity::plain, name + " frequency"));
    term.set_phase_rad(parse_quantity(item.substr(second + 1), Quantity::plain, name + " phase"));
    if (semicolon == std::string_view::npos) return terms;
    text.remove_prefix(semicolon + 1);
  }
  fail(field, "expected at most 16 terms");
}

std::uint32_t key_whole_number(const std::map<std::string, std::string>& keys, const std::string& key,
                               std::string_view field) {
  const double value = key_quantity(keys, key, Quantity::plain, field);
  if (value < 1.0 || value != std::floor(value) || value > 1e6) {
    fail(std::string(field) + " " + key, "expected a positive whole number, got '" + keys.at(key) + "'");
  }
  return static_cast<std::uint32_t>(value);
}

// feed=..,amax=..[,at=..]: speed along the contour, normal and tangential acceleration limits.
void parse_feed(const std::map<std::string, std::string>& keys, std::string_view field, netmc::v1::FeedRate& feed) {
  feed.set_feed_m_s(key_quantity(keys, "feed", Quantity::speed, field));
  feed.set_max_normal_acceleration_m_s2(key_quantity(keys, "amax", Quantity::acceleration, field));
  feed.set_max_tangential_acceleration_m_s2(key_quantity(keys, "at", Quantity::acceleration, field, 0.0));
}

// A shape timed either at a uniform rate (period=..) or by a feed-rate profile (feed=..,amax=..).
bool uses_feed(const std::map<std::string, std::string>& keys, std::string_view field, const std::string& shape) {
  const bool feed = keys.contains("feed") || keys.contains("amax") || keys.contains("at");
  if (feed && keys.contains("period")) {
    fail(field, shape + " takes period=.. (uniform rate) or feed=..,amax=.. (feed rate), not both");
  }
  return feed;
}

void require_kind_argument(const KindSpec& spec, std::string_view field, const std::string& form) {
  if (spec.argument.empty()) fail(field, "expected " + form);
}

}  // namespace

netmc::v1::Trajectory parse_trajectory(std::string_view text) {
  constexpr std::string_view field = "--trajectory";
  KindSpec spec = split_kind(text);
  netmc::v1::Trajectory out;
  if (spec.kind == "circle") {
    const auto keys = parse_keys(spec.argument, field,
                                 {"r", "cx", "cy", "period", "start", "cw", "revolutions"});
    auto& c = *out.mutable_circle();
    c.set_radius_m(key_quantity(keys, "r", Quantity::length, field));
    c.set_center_x_m(key_quantity(keys, "cx", Quantity::length, field, 0.0));
    c.set_center_y_m(key_quantity(keys, "cy", Quantity::length, field, 0.0));
    c.set_period_s(key_quantity(keys, "period", Quantity::time, field));
    c.set_start_angle_rad(key_quantity(keys, "start", Quantity::plain, field, 0.0));
    c.set_clockwise(key_quantity(keys, "cw", Quantity::plain, field, 0.0) != 0.0);
    c.set_revolutions(key_quantity(keys, "revolutions", Quantity::plain, field, 1.0));
  } else if (spec.kind == "ellipse") {
    const auto keys = parse_keys(spec.argument, field,
                                 {"a", "b", "cx", "cy", "period", "start", "cw", "revolutions", "feed", "amax", "at"});
    auto& e = *out.mutable_ellipse();
    e.set_semi_axis_x_m(key_quantity(keys, "a", Quantity::length, field));
    e.set_semi_axis_y_m(key_quantity(keys, "b", Quantity::length, field));
    e.set_center_x_m(key_quantity(keys, "cx", Quantity::length, field, 0.0));
    e.set_center_y_m(key_quantity(keys, "cy", Quantity::length, field, 0.0));
    if (uses_feed(keys, field, "ellipse")) {
      parse_feed(keys, field, *e.mutable_feed());
    } else {
      e.set_period_s(key_quantity(keys, "period", Quantity::time, field));
    }
    e.set_start_angle_rad(key_quantity(keys, "start", Quantity::plain, field, 0.0));
    e.set_clockwise(key_quantity(keys, "cw", Quantity::plain, field, 0.0) != 0.0);
    e.set_revolutions(key_quantity(keys, "revolutions", Quantity::plain, field, 1.0));
  } else if (spec.kind == "line") {
    const auto keys = parse_keys(spec.argument, field, {"x0", "y0", "x1", "y1", "duration"});
    auto& l = *out.mutable_line();
    l.set_x0_m(key_quantity(keys, "x0", Quantity::length, field));
    l.set_y0_m(key_quantity(keys, "y0", Quantity::length, field));
    l.set_x1_m(key_quantity(keys, "x1", Quantity::length, field));
    l.set_y1_m(key_quantity(keys, "y1", Quantity::length, field));
    l.set_duration_s(key_quantity(keys, "duration", Quantity::time, field));
  } else if (spec.kind == "lissajous") {
    const auto keys = parse_keys(spec.argument, field,
                                 {"ax", "ay", "p", "q", "phase", "cx", "cy", "period", "feed", "amax", "at"});
    auto& l = *out.mutable_lissajous();
    l.set_amplitude_x_m(key_quantity(keys, "ax", Quantity::length, field));
    l.set_amplitude_y_m(key_quantity(keys, "ay", Quantity::length, field));
    l.set_frequency_x(key_whole_number(keys, "p", field));
    l.set_frequency_y(key_whole_number(keys, "q", field));
    l.set_phase_rad(key_quantity(keys, "phase", Quantity::plain, field, 0.0));
    l.set_center_x_m(key_quantity(keys, "cx", Quantity::length, field, 0.0));
    l.set_center_y_m(key_quantity(keys, "cy", Quantity::length, field, 0.0));
    if (uses_feed(keys, field, "lissajous")) {
      parse_feed(keys, field, *l.mutable_feed());
    } else {
      l.set_period_s(key_quantity(keys, "period", Quantity::time, field));
    }
  } else if (spec.kind == "polyline") {
    const auto keys = parse_keys(spec.argument, field, {"points", "vmax", "amax", "corner"}, {"points"});
    auto& l = *out.mutable_polyline();
    *l.mutable_points() = parse_points(keys, field);
    l.set_max_speed_m_s(key_quantity(keys, "vmax", Quantity::speed, field));
    l.set_max_acceleration_m_s2(key_quantity(keys, "amax", Quantity::acceleration, field));
    l.set_corner_speed_m_s(key_quantity(keys, "corner", Quantity::speed, field, 0.0));
  } else if (spec.kind == "spline") {
    const auto keys = parse_keys(spec.argument, field, {"points", "feed", "amax", "at"}, {"points"});
    auto& s = *out.mutable_spline();
    *s.mutable_points() = parse_points(keys, field);
    parse_feed(keys, field, *s.mutable_feed());
  } else if (spec.kind == "multi-sine") {
    const auto keys = parse_keys(spec.argument, field, {"terms", "offset", "duration", "period"}, {"terms"});
    auto& m = *out.mutable_multi_sine();
    *m.mutable_terms() = parse_sine_terms(keys, field);
    m.set_offset_m(key_quantity(keys, "offset", Quantity::length, field, 0.0));
    m.set_duration_s(key_quantity(keys, "duration", Quantity::time, field));
    m.set_period_s(key_quantity(keys, "period", Quantity::time, field, 0.0));
  } else {
    fail(field, "unknown shape '" + spec.kind +
                    "' (expected circle:r=..,cx=..,cy=..,period=.., ellipse:a=..,b=..,cx=..,cy=..,"
                    "period=.., line:x0=..,y0=..,x1=..,y1=..,duration=.., "
                    "lissajous:ax=..,ay=..,p=..,q=..,period=.., polyline:points=X,Y;X,Y;..,vmax=..,amax=.., "
                    "spline:points=X,Y;X,Y;..,feed=..,amax=.. or, for one axis, "
                    "multi-sine:terms=A/F/P;..,offset=..,duration=..)");
  }
  return out;
}

netmc::v1::DelayProfile parse_delay(std::string_view text, std::string_view flag) {
  KindSpec spec = split_kind(text);
  netmc::v1::DelayProfile out;
  const auto range = [&](const std::string& value, const std::string& key,
                         netmc::v1::UniformDelay& target) {
    const std::size_t dots = value.find("..");
    if (dots == std::string::npos) {
      fail(flag, "key '" + key + "' expects a range MIN..MAX such as 0.3ms..0.8ms, got '" + value + "'");
    }
    target.set_min_s(parse_quantity(value.substr(0, dots), Quantity::time, std::string(flag) + " " + key));
    target.set_max_s(parse_quantity(value.substr(dots + 2), Quantity::time, std::string(flag) + " " + key));
  };
  if (spec.kind == "none") {
    out.mutable_none();
  } else if (spec.kind == "constant") {
    require_kind_argument(spec, flag, "constant:DURATION such as constant:1ms");
    out.set_constant_s(parse_quantity(spec.argument, Quantity::time, flag));
  } else if (spec.kind == "uniform") {
    const auto keys = parse_keys(spec.argument, flag, {"min", "max"});
    out.mutable_uniform()->set_min_s(key_quantity(keys, "min", Quantity::time, flag));
    out.mutable_uniform()->set_max_s(key_quantity(keys, "max", Quantity::time, flag));
  } else if (spec.kind == "normal") {
    const auto keys = parse_keys(spec.argument, flag, {"mean", "sd", "min", "max"});
    auto& n = *out.mutable_normal();
    n.set_mean_s(key_quantity(keys, "mean", Quantity::time, flag));
    n.set_stddev_s(key_quantity(keys, "sd", Quantity::time, flag));
    n.set_min_s(key_quantity(keys, "min", Quantity::time, flag, 0.0));
    n.set_max_s(key_quantity(keys, "max", Quantity::time, flag, 0.0));
  } else if (spec.kind == "pareto") {
    const auto keys = parse_keys(spec.argument, flag, {"scale", "shape", "max"});
    auto& p = *out.mutable_pareto();
    p.set_scale_s(key_quantity(keys, "scale", Quantity::time, flag));
    p.set_shape(key_quantity(keys, "shape", Quantity::plain, flag));
    p.set_max_s(key_quantity(keys, "max", Quantity::time, flag, 0.0));
  } else if (spec.kind == "markov") {
    const auto keys = parse_keys(spec.argument, flag, {"good", "bad", "p_gb", "p_bg"});
    auto& m = *out.mutable_markov();
    if (!keys.contains("good") || !keys.contains("bad")) {
      fail(flag, "markov expects good=MIN..MAX,bad=MIN..MAX,p_gb=P,p_bg=P");
    }
    range(keys.at("good"), "good", *m.mutable_good());
    range(keys.at("bad"), "bad", *m.mutable_bad());
    m.set_p_good_to_bad(key_quantity(keys, "p_gb", Quantity::plain, flag));
    m.set_p_bad_to_good(key_quantity(keys, "p_bg", Quantity::plain, flag));
  } else if (spec.kind == "trace") {
    require_kind_argument(spec, flag, "trace:FILE[,rtt_share=F]");
    // FILE: a CSV of delays, or `ping -D` output (each round trip's rtt_share, default 0.5, is a
    // one-way delay); the option is split off the end, a path may hold commas.
    std::string path = spec.argument;
    constexpr std::string_view kShare = ",rtt_share=";
    if (const auto at = path.rfind(kShare); at != std::string::npos) {
      const double share = parse_quantity(path.substr(at + kShare.size()), Quantity::plain, std::string(flag) + " rtt_share");
      if (!(share > 0.0 && share <= 1.0)) fail(flag, "rtt_share: expected a number in (0, 1], e.g. 0.5");
      out.mutable_trace()->set_round_trip_share(share);
      path.resize(at);
    }
    out.mutable_trace()->set_path(path);
  } else {
    fail(flag, "unknown delay '" + spec.kind +
                   "' (expected none, constant:D, uniform:min=..,max=.., normal:mean=..,sd=.., "
                   "pareto:scale=..,shape=.., markov:good=..,bad=..,p_gb=..,p_bg=.. or trace:FILE[,rtt_share=F])");
  }
  return out;
}

netmc::v1::LossProfile parse_loss(std::string_view text, std::string_view flag) {
  KindSpec spec = split_kind(text);
  netmc::v1::LossProfile out;
  if (spec.kind == "none") {
    return out;
  } else if (spec.kind == "bernoulli") {
    const auto keys = parse_keys(spec.argument, flag, {"p"});
    out.mutable_bernoulli()->set_p(key_quantity(keys, "p", Quantity::plain, flag));
  } else if (spec.kind == "gilbert") {
    const auto keys = parse_keys(spec.argument, flag, {"p_gb", "p_bg", "good", "bad"});
    auto& g = *out.mutable_gilbert_elliott();
    g.set_p_good_to_bad(key_quantity(keys, "p_gb", Quantity::plain, flag));
    g.set_p_bad_to_good(key_quantity(keys, "p_bg", Quantity::plain, flag));
    g.set_loss_in_good(key_quantity(keys, "good", Quantity::plain, flag, 0.0));
    g.set_loss_in_bad(key_quantity(keys, "bad", Quantity::plain, flag, 1.0));
  } else {
    fail(flag, "unknown loss '" + spec.kind +
                   "' (expected none, bernoulli:p=P or gilbert:p_gb=..,p_bg=..[,good=..,bad=..])");
  }
  return out;
}

netmc::v1::Position parse_position(std::string_view text, std::string_view flag) {
  const auto keys = parse_keys(text, flag, {"x", "y"});
  if (!keys.contains("x") || !keys.contains("y")) fail(flag, "expected x=LENGTH,y=LENGTH");
  netmc::v1::Position position;
  position.set_x_m(parse_quantity(keys.at("x"), Quantity::length, std::string(flag) + " x"));
  position.set_y_m(parse_quantity(keys.at("y"), Quantity::length, std::string(flag) + " y"));
  return position;
}

namespace {

// The job's settings for `axis`, added when it has none yet.
netmc::v1::PlantAxisSettings& plant_axis(netmc::v1::JobSpec& job, const std::string& axis) {
  for (auto& settings : *job.mutable_plant_axes()) {
    if (settings.axis() == axis) return settings;
  }
  auto& settings = *job.add_plant_axes();
  settings.set_axis(axis);
  return settings;
}

// An axis of the job, or a message naming the flag and the job's axes.
std::string job_axis(const netmc::v1::JobSpec& job, std::string_view axis, std::string_view flag) {
  const auto names = job::axis_names(job);
  if (std::find(names.begin(), names.end(), axis) == names.end()) {
    std::string expected;
    for (const auto& name : names) expected += (expected.empty() ? "" : ", ") + name;
    throw std::invalid_argument(std::string(flag) + ": unknown axis '" + std::string(axis.substr(0, 64)) +
                                "' (expected one of: " + expected + ")");
  }
  return std::string(axis);
}

}  // namespace

void parse_plant(std::string_view text, netmc::v1::JobSpec& job) {
  // fmu:PATH.fmu[:...] and plugin:PATH.so[:...]: the whole text names the plant; its options are
  // the file's (server/fmu/fmu_plant_options.hpp, server/plugins/component_plugin_spec.hpp).
  if (job::is_file_plant(trim(text))) {
    job.set_plant(std::string(trim(text)));
    return;
  }
  const std::size_t colon = text.find(':');
  const std::string name(trim(text.substr(0, colon)));
  if (name.empty()) throw std::invalid_argument("--plant: expected NAME[:KEY=VALUE,...], got '" + std::string(text) + "'");
  job.set_plant(name);
  if (colon == std::string_view::npos) return;
  for (const auto& item : split_list(std::string(text.substr(colon + 1)))) {
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw std::invalid_argument("--plant: expected [AXIS.]KEY=VALUE, got '" + item + "'");
    }
    const std::string target = item.substr(0, equals);
    const double value = parse_quantity(item.substr(equals + 1), Quantity::plain, "--plant " + target);
    const std::size_t dot = target.find('.');
    std::vector<std::string> axes;
    if (dot == std::string::npos) {
      axes = job::axis_names(job);
    } else {
      axes.push_back(job_axis(job, target.substr(0, dot), "--plant"));
    }
    const std::string key = dot == std::string::npos ? target : target.substr(dot + 1);
    for (const auto& axis : axes) {
      auto& parameter = *plant_axis(job, axis).add_parameters();
      parameter.set_key(key);
      parameter.set_value(value);
    }
  }
}

void parse_disturbance(std::string_view text, netmc::v1::JobSpec& job) {
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos) {
    throw std::invalid_argument("--disturbance: expected AXIS:step=..,on=..,off=.. | sine=..,hz=.. | noise=..,band=.. "
                                "| constant=.., got '" + std::string(text) + "'");
  }
  const std::string axis = job_axis(job, trim(text.substr(0, colon)), "--disturbance");
  const auto keys = parse_keys(text.substr(colon + 1), "--disturbance",
                               {"constant", "step", "on", "off", "sine", "hz", "phase", "noise", "band", "seed"});
  auto& d = *plant_axis(job, axis).mutable_disturbance();
  for (const auto& [key, value] : keys) {
    const std::string field = "--disturbance " + key;
    const bool is_time = key == "on" || key == "off";
    const double number = parse_quantity(value, is_time ? Quantity::time : Quantity::plain, field);
    if (key == "constant") d.set_constant(number);
    if (key == "step") d.mutable_step()->set_amplitude(number);
    if (key == "on") d.mutable_step()->set_on_s(number);
    if (key == "off") d.mutable_step()->set_off_s(number);
    if (key == "sine") d.mutable_sine()->set_amplitude(number);
    if (key == "hz") d.mutable_sine()->set_frequency_hz(number);
    if (key == "phase") d.mutable_sine()->set_phase_rad(number);
    if (key == "noise") d.mutable_noise()->set_stddev(number);
    if (key == "band") d.mutable_noise()->set_bandwidth_hz(number);
    if (key == "seed") {
      if (!(number >= 1.0 && number <= 9.0e15 && number == std::floor(number))) {
        throw std::invalid_argument("--disturbance seed: expected a whole number in [1, 9e15]");
      }
      d.mutable_noise()->set_seed(static_cast<std::uint64_t>(number));
    }
  }
}

void parse_dead_zone_inverse(std::string_view text, netmc::v1::JobSpec& job) {
  constexpr std::string_view flag = "--dead-zone-inverse";
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos) {
    throw std::invalid_argument("--dead-zone-inverse: expected AXIS:b_r=..,b_l=..[,m_r=..,m_l=..] (volts, slopes V/V), got '" +
                                std::string(text.substr(0, 80)) + "'");
  }
  const std::string axis = job_axis(job, trim(text.substr(0, colon)), flag);
  const auto keys = parse_keys(text.substr(colon + 1), flag, {"b_r", "b_l", "m_r", "m_l"});
  auto* controller = job.mutable_controller();
  netmc::v1::AxisDeadZone* entry = nullptr;
  for (auto& existing : *controller->mutable_dead_zone_inverse()) {
    if (existing.axis() == axis) entry = &existing;
  }
  if (!entry) {
    entry = controller->add_dead_zone_inverse();
    entry->set_axis(axis);
  }
  auto& d = *entry->mutable_dead_zone();
  d.set_right_break_v(key_quantity(keys, "b_r", Quantity::plain, flag));
  d.set_left_break_v(key_quantity(keys, "b_l", Quantity::plain, flag));
  d.set_right_slope(key_quantity(keys, "m_r", Quantity::plain, flag, 1.0));
  d.set_left_slope(key_quantity(keys, "m_l", Quantity::plain, flag, 1.0));
}

}  // namespace netmc::cli
