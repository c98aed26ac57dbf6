#include "server/console/prometheus_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace netmc::console {
namespace {

bool is_name(std::string_view name, bool colons) {
  if (name.empty() || name.size() > 200) return false;
  const auto head = [&](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || (colons && c == ':'); };
  const auto tail = [&](char c) { return head(c) || (c >= '0' && c <= '9'); };
  return head(name.front()) && std::all_of(name.begin() + 1, name.end(), tail);
}

}  // namespace

std::string escape_label_value(std::string_view value) {
  std::string out;
  out.reserve(value.size());
  for (const char c : value) {
    if (c == '\\') out += "\\\\";
    else if (c == '"') out += "\\\"";
    else if (c == '\n') out += "\\n";
    else out += c;
  }
  return out;
}

std::string format_sample_value(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
  return fmt::format("{}", value);
}

void PrometheusPage::family(std::string_view name, MetricType type, std::string_view help) {
  if (!is_name(name, true)) throw std::invalid_argument("metric name '" + std::string(name) + "' is not a Prometheus name");
  if (std::find(names_.begin(), names_.end(), name) != names_.end()) {
    throw std::invalid_argument("metric " + std::string(name) + " added twice");
  }
  if (type == MetricType::counter && !name.ends_with("_total")) {
    throw std::invalid_argument("counter " + std::string(name) + " must end in _total");
  }
  names_.emplace_back(name);
  current_ = name;
  current_type_ = type;
  std::string escaped_help;
  for (const char c : help) {
    if (c == '\\') escaped_help += "\\\\";
    else if (c == '\n') escaped_help += "\\n";
    else escaped_help += c;
  }
  const char* type_name = type == MetricType::counter ? "counter" : type == MetricType::gauge ? "gauge" : "summary";
  // A counter's family is named without _total in HELP and TYPE (OpenMetrics); the 0.0.4 text
  // format names it as its samples, which promtool expects.
  text_ += fmt::format("# HELP {} {}\n# TYPE {} {}\n", name, escaped_help, name, type_name);
}

void PrometheusPage::sample(const MetricLabels& labels, double value, std::string_view suffix) {
  if (current_.empty()) throw std::invalid_argument("a sample outside a metric family");
  if (!suffix.empty() && !(current_type_ == MetricType::summary && (suffix == "_sum" || suffix == "_count"))) {
    throw std::invalid_argument("metric " + current_ + ": suffix '" + std::string(suffix) + "' is not a summary's");
  }
  text_ += current_;
  text_ += suffix;
  if (!labels.empty()) {
    text_ += '{';
    bool first = true;
    for (const auto& [name, label_value] : labels) {
      if (!is_name(name, false) || name.starts_with("__")) {
        throw std::invalid_argument("metric " + current_ + ": label name '" + name + "' is not a Prometheus name");
      }
      if (!first) text_ += ',';
      first = false;
      text_ += fmt::format("{}=\"{}\"", name, escape_label_value(label_value));
    }
    text_ += '}';
  }
  text_ += ' ';
  text_ += format_sample_value(value);
  text_ += '\n';
}

}  // namespace netmc::console
