#include "client/sweep_grid.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "server/job/delay_compensators.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::cli {
namespace {

// A grid this large would take hours; it is almost certainly a typo in a range.
constexpr std::size_t kMaxAxisValues = 10000;
constexpr std::size_t kMaxConfigurations = 1000000;
constexpr double kPaperDelayMinS = 0.3e-3;  // paper 001: tau ~ U(0.3, 0.8) ms

std::uint64_t parse_seed(std::string_view text, const std::string& whole) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    throw std::invalid_argument("--seeds: expected FIRST..LAST or a list such as 1,4,9 (non-negative "
                                "integers), got '" + whole + "'");
  }
  return value;
}

}  // namespace

std::vector<double> parse_value_axis(const std::string& text, Quantity quantity,
                                     std::string_view flag) {
  const std::string form = std::string(flag) + ": expected START:STOP:COUNT (e.g. 0.5ms:10ms:20) or a list "
                           "(e.g. 1ms,2ms,5ms)";
  std::vector<double> values;
  if (text.find(':') != std::string::npos) {
    const std::size_t first = text.find(':');
    const std::size_t second = text.find(':', first + 1);
    if (second == std::string::npos || text.find(':', second + 1) != std::string::npos) {
      throw std::invalid_argument(form + ", got '" + text + "'");
    }
    const double start = parse_quantity(text.substr(0, first), quantity, std::string(flag) + " START");
    const double stop = parse_quantity(text.substr(first + 1, second - first - 1), quantity,
                                       std::string(flag) + " STOP");
    const std::string count_text = text.substr(second + 1);
    std::size_t count = 0;
    const auto [end, error] = std::from_chars(count_text.data(), count_text.data() + count_text.size(), count);
    if (count_text.empty() || error != std::errc() || end != count_text.data() + count_text.size() ||
        count < 2 || count > kMaxAxisValues) {
      throw std::invalid_argument(fmt::format("{} COUNT: expected an integer from 2 to {}, got '{}'", flag,
                                              kMaxAxisValues, count_text));
    }
    if (!(stop > start)) {
      throw std::invalid_argument(fmt::format("{}: expected STOP above START, got '{}'", flag, text));
    }
    for (std::size_t i = 0; i < count; ++i) {
      values.push_back(start + (stop - start) * static_cast<double>(i) / static_cast<double>(count - 1));
    }
    return values;
  }
  const auto items = split_list(text);
  if (items.empty()) throw std::invalid_argument(form + ", got '" + text + "'");
  if (items.size() > kMaxAxisValues) {
    throw std::invalid_argument(fmt::format("{}: at most {} values", flag, kMaxAxisValues));
  }
  for (const auto& item : items) values.push_back(parse_quantity(item, quantity, flag));
  return values;
}

std::vector<std::uint64_t> parse_seed_axis(const std::string& text) {
  std::vector<std::uint64_t> seeds;
  const std::size_t dots = text.find("..");
  if (dots != std::string::npos) {
    const std::uint64_t first = parse_seed(std::string_view(text).substr(0, dots), text);
    const std::uint64_t last = parse_seed(std::string_view(text).substr(dots + 2), text);
    if (last < first || last - first >= kMaxAxisValues) {
      throw std::invalid_argument(fmt::format(
          "--seeds: expected FIRST..LAST with FIRST <= LAST and at most {} seeds, got '{}'",
          kMaxAxisValues, text));
    }
    for (std::uint64_t seed = first; seed <= last; ++seed) seeds.push_back(seed);
    return seeds;
  }
  const auto items = split_list(text);
  if (items.empty()) parse_seed("", text);
  for (const auto& item : items) seeds.push_back(parse_seed(item, text));
  return seeds;
}

std::optional<double> delay_upper_bound_s(const netmc::v1::DelayProfile& d) {
  // The grid's axis value: the profile's bound (job::delay_profile_bound_s), an untruncated
  // normal's mean + 6 sd, and none for a trace (its rows name no bound).
  if (d.has_normal() && !(d.normal().max_s() > 0.0)) return d.normal().mean_s() + 6.0 * d.normal().stddev_s();
  if (d.has_trace()) return std::nullopt;
  return job::delay_profile_bound_s(d);
}

std::vector<SweepConfiguration> expand_sweep(const SweepAxes& axes) {
  if (!axes.delays.empty() && !axes.delay_max.empty()) {
    throw std::invalid_argument("--delay-max: cannot be combined with --delay (give one delay axis)");
  }
  if (!axes.delay_min.empty() && axes.delay_max.empty()) {
    throw std::invalid_argument("--delay-min: only meaningful with --delay-max");
  }
  if (!axes.fixed.spec_file.empty() && !axes.presets.empty()) {
    throw std::invalid_argument("--spec: cannot be combined with --preset");
  }

  // The delay axis: none given keeps each job's own delay.
  std::vector<netmc::v1::DelayProfile> delays;
  for (const auto& text : axes.delays) delays.push_back(parse_delay(text, "--delay"));
  if (!axes.delay_max.empty()) {
    const double minimum = axes.delay_min.empty()
                               ? kPaperDelayMinS
                               : parse_quantity(axes.delay_min, Quantity::time, "--delay-min");
    if (!(minimum >= 0.0)) {
      throw std::invalid_argument("--delay-min: expected a non-negative duration such as 0.3ms");
    }
    for (const double maximum : parse_value_axis(axes.delay_max, Quantity::time, "--delay-max")) {
      if (!(maximum >= minimum)) {
        throw std::invalid_argument(fmt::format(
            "--delay-max: every value must be at least --delay-min ({} ms), got {} ms (set "
            "--delay-min lower)", minimum * 1e3, maximum * 1e3));
      }
      netmc::v1::DelayProfile delay;
      delay.mutable_uniform()->set_min_s(minimum);
      delay.mutable_uniform()->set_max_s(maximum);
      delays.push_back(delay);
    }
  }
  const std::vector<std::uint64_t> seeds =
      axes.seeds.empty() ? std::vector<std::uint64_t>{} : parse_seed_axis(axes.seeds);
  // The compensator axis: --compensate none,predictor makes each run once per compensator (name,
  // spec; no spec for none).
  std::vector<std::pair<std::string, std::optional<netmc::v1::CompensationSpec>>> compensators;
  if (!axes.fixed.compensate.empty()) {
    for (const auto& name : split_list(axes.fixed.compensate)) {
      compensators.emplace_back(name, job::parse_compensation(name, "--compensate"));
    }
    if (compensators.empty()) throw std::invalid_argument("--compensate: expected NAME[,NAME...]");
  }

  // Base studies: each preset (or the spec file), with each trajectory.
  std::vector<std::string> presets = axes.presets;
  if (presets.empty()) presets.push_back(axes.fixed.spec_file.empty() ? "seed001" : "");
  std::vector<std::string> trajectories = axes.trajectories;
  if (trajectories.empty()) trajectories.push_back("");

  std::vector<SweepConfiguration> grid;
  for (const auto& preset : presets) {
    for (const auto& trajectory : trajectories) {
      StudyFlags flags = axes.fixed;
      flags.preset = preset;
      flags.trajectory = trajectory;
      flags.controllers = axes.controllers;
      flags.compensate.clear();  // an axis of the grid, applied below
      StudyPlan plan = plan_from_flags(flags);
      if (!compensators.empty()) {
        std::vector<netmc::v1::JobSpec> runs;
        for (const auto& run : plan.jobs) {
          for (const auto& [name, compensation] : compensators) {
            netmc::v1::JobSpec job = run;
            if (compensation) {
              *job.mutable_compensation() = *compensation;
              // Labelled RUN/COMPENSATOR, so that tables and figures keep the runs apart.
              job.set_name((run.name().empty() ? run.controller().name() : run.name()) + "/" + name);
            } else {
              job.clear_compensation();
            }
            runs.push_back(std::move(job));
          }
        }
        plan.jobs = std::move(runs);
      }
      std::string base = preset.empty() ? axes.fixed.spec_file : preset;
      if (!trajectory.empty()) base += "/" + trajectory;
      for (const auto& run : plan.jobs) {
        const std::size_t delay_count = delays.empty() ? 1 : delays.size();
        const std::size_t seed_count = seeds.empty() ? 1 : seeds.size();
        if (grid.size() + delay_count * seed_count > kMaxConfigurations) {
          throw std::invalid_argument(fmt::format(
              "sweep: the grid has more than {} configurations; narrow an axis", kMaxConfigurations));
        }
        for (std::size_t d = 0; d < delay_count; ++d) {
          for (std::size_t s = 0; s < seed_count; ++s) {
            SweepConfiguration configuration;
            configuration.job = run;
            if (!delays.empty()) *configuration.job.mutable_downlink()->mutable_delay() = delays[d];
            if (!seeds.empty()) configuration.job.set_seed(seeds[s]);
            job::apply_defaults(configuration.job);
            configuration.number = grid.size() + 1;
            configuration.base = base;
            configuration.label = run.name().empty() ? run.controller().name() : run.name();
            configuration.delay_max_s = delay_upper_bound_s(configuration.job.downlink().delay());
            configuration.seed = configuration.job.seed();
            grid.push_back(std::move(configuration));
          }
        }
      }
    }
  }
  return grid;
}

}  // namespace netmc::cli
