#include "client/sweep_output.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <google/protobuf/descriptor.h>
#include <google/protobuf/reflection.h>

#include <algorithm>
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "server/job/job_builder.hpp"

namespace netmc::cli {
namespace {

using google::protobuf::FieldDescriptor;

constexpr std::array<const char*, 3> kAxisNames{"x", "y", "z"};

// tracking_rms_m -> tracking_rms_x_m; command_rms -> command_rms_x.
std::string axis_column(const std::string& field, const char* axis) {
  for (const char* unit : {"_m", "_s"}) {
    const std::string suffix(unit);
    if (field.size() > suffix.size() && field.compare(field.size() - suffix.size(), suffix.size(), suffix) == 0) {
      return field.substr(0, field.size() - suffix.size()) + "_" + axis + suffix;
    }
  }
  return field + "_" + axis;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

std::string format_value(const google::protobuf::Message& message, const FieldDescriptor* field,
                         int index) {
  const auto* reflection = message.GetReflection();
  const bool repeated = field->is_repeated();
  if (repeated && index >= reflection->FieldSize(message, field)) return "";
  // A metric the iteration does not have (the steady ones without an evaluation window) is an
  // empty cell, not 0.
  if (!repeated && field->has_presence() && !reflection->HasField(message, field)) return "";
  switch (field->cpp_type()) {
    case FieldDescriptor::CPPTYPE_DOUBLE:
      // Shortest text that reads back as the same double.
      return fmt::format("{}", repeated ? reflection->GetRepeatedDouble(message, field, index)
                                            : reflection->GetDouble(message, field));
    case FieldDescriptor::CPPTYPE_UINT32:
      return fmt::format("{}", repeated ? reflection->GetRepeatedUInt32(message, field, index)
                                        : reflection->GetUInt32(message, field));
    case FieldDescriptor::CPPTYPE_BOOL:
      return (repeated ? reflection->GetRepeatedBool(message, field, index)
                       : reflection->GetBool(message, field))
                 ? "1"
                 : "0";
    default:
      break;
  }
  throw std::logic_error("sweep csv: IterationMetrics." + field->name() + " has an unsupported type");
}

const std::vector<const FieldDescriptor*>& metric_fields() {
  static const std::vector<const FieldDescriptor*> fields = [] {
    std::vector<const FieldDescriptor*> out;
    const auto* descriptor = netmc::v1::IterationMetrics::descriptor();
    // Scalars and per-axis lists; the controller's estimates (messages) are in the JSON only.
    for (int i = 0; i < descriptor->field_count(); ++i) {
      if (descriptor->field(i)->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE) out.push_back(descriptor->field(i));
    }
    return out;
  }();
  return fields;
}

std::string optional_number(const std::optional<double>& value) {
  return value ? fmt::format("{}", *value) : std::string();
}

}  // namespace

std::vector<std::string> sweep_csv_columns(std::size_t axes) {
  axes = std::clamp<std::size_t>(axes, 2, kAxisNames.size());
  std::vector<std::string> columns{"config", "base", "run", "controller", "plant", "trajectory",
                                   "delay", "delay_max_s", "seed", "sample_period_s"};
  for (const auto* field : metric_fields()) {
    if (field->is_repeated()) {
      for (std::size_t axis = 0; axis < axes; ++axis) columns.push_back(axis_column(field->name(), kAxisNames[axis]));
    } else {
      columns.push_back(field->name());
    }
  }
  return columns;
}

std::string sweep_csv(const std::vector<SweepConfiguration>& grid,
                      const std::vector<RunOutcome>& outcomes) {
  std::string csv;
  // Per-axis columns for x, y, and z where a run has a third axis (empty in two-axis rows). The
  // grid's own jobs count too, so that a shard of it (sweep_shard.hpp) has the whole grid's columns.
  std::size_t axes = 2;
  for (const auto& configuration : grid) {
    if (job::is_spatial_job(configuration.job)) axes = 3;
  }
  for (const auto& outcome : outcomes) {
    for (const auto& metrics : outcome.result.iterations()) {
      axes = std::max(axes, static_cast<std::size_t>(metrics.tracking_rms_m_size()));
    }
  }
  axes = std::min(axes, kAxisNames.size());
  const auto columns = sweep_csv_columns(axes);
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) csv += ',';
    csv += columns[i];
  }
  csv += "\n";
  for (std::size_t c = 0; c < grid.size(); ++c) {
    const auto& configuration = grid[c];
    const auto& result = outcomes.at(c).result;
    const std::string prefix = fmt::format(
        "{},{},{},{},{},{},{},{},{},{}", configuration.number, csv_field(configuration.base),
        csv_field(configuration.label), csv_field(result.controller()), csv_field(result.plant()),
        csv_field(result.trajectory()), csv_field(result.delay()),
        optional_number(configuration.delay_max_s), configuration.seed, result.sample_period_s());
    for (const auto& metrics : result.iterations()) {
      csv += prefix;
      for (const auto* field : metric_fields()) {
        if (field->is_repeated()) {
          for (std::size_t axis = 0; axis < axes; ++axis) {
            csv += ',';
            csv += format_value(metrics, field, static_cast<int>(axis));
          }
        } else {
          csv += ',';
          csv += format_value(metrics, field, 0);
        }
      }
      csv += "\n";
    }
  }
  return csv;
}

std::string sweep_json(const std::vector<SweepConfiguration>& grid,
                       const std::vector<RunOutcome>& outcomes) {
  nlohmann::ordered_json configurations = nlohmann::ordered_json::array();
  for (std::size_t c = 0; c < grid.size(); ++c) {
    const auto& configuration = grid[c];
    nlohmann::ordered_json entry;
    entry["config"] = configuration.number;
    entry["base"] = configuration.base;
    entry["run"] = configuration.label;
    entry["delay_max_s"] = configuration.delay_max_s ? nlohmann::ordered_json(*configuration.delay_max_s)
                                                     : nlohmann::ordered_json(nullptr);
    entry["seed"] = configuration.seed;
    entry["result"] = nlohmann::ordered_json::parse(job::to_json(outcomes.at(c).result));
    configurations.push_back(std::move(entry));
  }
  nlohmann::ordered_json document;
  document["configurations"] = std::move(configurations);
  return document.dump(1) + "\n";
}

void print_sweep_summary(std::ostream& out, const std::vector<SweepConfiguration>& grid,
                         const std::vector<RunOutcome>& outcomes) {
  // (base, delay) -> run -> (sum of e_max over seeds, count, unstable count)
  struct Cell { double sum_m = 0.0; int count = 0; int unstable = 0; int not_following = 0; };
  std::vector<std::string> runs;
  std::map<std::pair<std::string, double>, std::map<std::string, Cell>> table;
  std::vector<std::pair<std::string, double>> row_order;
  for (std::size_t c = 0; c < grid.size(); ++c) {
    const auto& configuration = grid[c];
    const auto& iterations = outcomes.at(c).result.iterations();
    if (iterations.empty()) continue;
    const auto& last = iterations[iterations.size() - 1];
    const std::pair<std::string, double> row{configuration.base, configuration.delay_max_s.value_or(-1.0)};
    if (!table.contains(row)) row_order.push_back(row);
    if (std::find(runs.begin(), runs.end(), configuration.label) == runs.end()) runs.push_back(configuration.label);
    Cell& cell = table[row][configuration.label];
    if (last.diverged()) {
      ++cell.unstable;
    } else if (last.did_not_follow()) {
      ++cell.not_following;  // its e_max is no result (study_report.cpp)
    } else {
      cell.sum_m += last.e_max_m();
      ++cell.count;
    }
  }
  fmt::print(out, "e_max [mm] of the last iteration, mean over seeds (u: unstable in every seed, "
                  "*: unstable in some; n: did not follow the reference in every seed, +: in some)\n\n");
  fmt::print(out, "{:<16} {:>13}", "base", "delay max [ms]");
  for (const auto& run : runs) fmt::print(out, " {:>17}", run);
  fmt::print(out, "\n");
  for (const auto& row : row_order) {
    fmt::print(out, "{:<16} {:>13}", row.first.size() > 16 ? row.first.substr(0, 15) + "~" : row.first,
               row.second < 0.0 ? std::string("-") : fmt::format("{:.3f}", row.second * 1e3));
    for (const auto& run : runs) {
      const auto found = table[row].find(run);
      if (found == table[row].end()) {
        fmt::print(out, " {:>17}", "");
        continue;
      }
      const Cell& cell = found->second;
      if (cell.count == 0) {
        fmt::print(out, " {:>17}", cell.unstable > 0 ? "u" : "n");
      } else {
        fmt::print(out, " {:>16.4f}{}", cell.sum_m / cell.count * 1e3,
                   cell.unstable > 0 ? "*" : cell.not_following > 0 ? "+" : " ");
      }
    }
    fmt::print(out, "\n");
  }
}

}  // namespace netmc::cli
