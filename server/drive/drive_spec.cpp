#include "server/drive/drive_spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <set>
#include <stdexcept>

#include "plant/plant_catalog.hpp"

namespace netmc::drive {
namespace {

constexpr std::size_t kMaxSpecLength = 4096;
constexpr const char* kForms =
    "sim:PLANT[:KEY=VALUE,...], modbus-tcp:HOST:PORT[,unit=N,map=FILE,timeout=DURATION] or "
    "plugin:PATH.so[:KEY=VALUE,...], for every axis or as AXIS=SPEC";

std::string quoted(const std::string& text) { return "'" + text.substr(0, 80) + (text.size() > 80 ? "...'" : "'"); }

bool printable(const std::string& text) {
  return std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
}

}  // namespace

bool parse_finite_decimal(const std::string& text, double& value) {
  if (text.empty() || text.size() > 64 || text.find_first_not_of("0123456789+-.eE") != std::string::npos) {
    return false;
  }
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

std::string DriveSpec::describe() const {
  switch (kind) {
    case Kind::simulated: return "sim:" + text;
    case Kind::modbus_tcp: return "modbus-tcp:" + text;
    case Kind::plugin: return "plugin:" + text;
  }
  return text;
}

std::string DriveSpec::plant() const {
  // An FMU's or a plugin's plant: its whole text (its options are the file's).
  if (plant::is_file_plant(text)) return text;
  return text.substr(0, text.find(':'));
}

std::vector<std::pair<std::string, double>> DriveSpec::plant_overrides() const {
  std::vector<std::pair<std::string, double>> out;
  const std::size_t colon = text.find(':');
  if (kind != Kind::simulated || colon == std::string::npos || plant::is_file_plant(text)) return out;
  std::string rest = text.substr(colon + 1);
  std::size_t start = 0;
  while (start <= rest.size()) {
    const std::size_t comma = std::min(rest.find(',', start), rest.size());
    const std::string item = rest.substr(start, comma - start);
    const std::size_t equals = item.find('=');
    double value = 0.0;
    if (equals == std::string::npos || equals == 0 || !parse_finite_decimal(item.substr(equals + 1), value)) {
      throw std::invalid_argument("--drive " + describe().substr(0, 80) + ": expected KEY=NUMBER after the plant, got " +
                                  quoted(item));
    }
    out.emplace_back(item.substr(0, equals), value);
    start = comma + 1;
  }
  return out;
}

DriveSpec parse_drive_spec(const std::string& text) {
  if (text.size() > kMaxSpecLength || !printable(text)) {
    throw std::invalid_argument("--drive: expected " + std::string(kForms) + " (printable, at most 4096 characters)");
  }
  const std::size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  DriveSpec spec;
  if (kind == "sim") {
    spec.kind = DriveSpec::Kind::simulated;
  } else if (kind == "modbus-tcp") {
    spec.kind = DriveSpec::Kind::modbus_tcp;
  } else if (kind == "plugin") {
    spec.kind = DriveSpec::Kind::plugin;
  } else {
    throw std::invalid_argument("--drive: unknown drive " + quoted(text) + " (expected " + kForms + ")");
  }
  if (colon == std::string::npos || colon + 1 == text.size()) {
    throw std::invalid_argument("--drive " + quoted(text) + ": nothing after '" + kind + ":' (expected " + kForms + ")");
  }
  spec.text = text.substr(colon + 1);
  if (spec.kind == DriveSpec::Kind::simulated) spec.plant_overrides();  // checked now
  return spec;
}

std::map<std::string, DriveSpec> parse_drive_flags(const std::vector<std::string>& values,
                                                   const std::vector<std::string>& axes, const std::string& plant) {
  std::map<std::string, DriveSpec> by_axis;
  std::optional<DriveSpec> every;
  for (const auto& value : values) {
    // AXIS=SPEC: the part before the first '=' names an axis (no ':' in it).
    const std::size_t equals = value.find('=');
    const std::string head = value.substr(0, equals);
    if (equals != std::string::npos && head.find(':') == std::string::npos) {
      if (std::find(axes.begin(), axes.end(), head) == axes.end()) {
        throw std::invalid_argument("--drive " + quoted(value) + ": " + quoted(head) + " is not an axis of this node");
      }
      if (!by_axis.emplace(head, parse_drive_spec(value.substr(equals + 1))).second) {
        throw std::invalid_argument("--drive: two drives for axis " + head);
      }
    } else {
      if (every) throw std::invalid_argument("--drive: one spec for every axis, or AXIS=SPEC entries: got two of the first");
      every = parse_drive_spec(value);
    }
  }
  const DriveSpec fallback = every ? *every : DriveSpec{DriveSpec::Kind::simulated, plant};
  std::set<std::string> hardware;
  for (const auto& axis : axes) {
    const DriveSpec& spec = by_axis.count(axis) ? by_axis.at(axis) : fallback;
    if (spec.kind != DriveSpec::Kind::simulated && !hardware.insert(spec.describe()).second) {
      throw std::invalid_argument("--drive " + quoted(spec.describe()) +
                                  " serves one axis: give each axis its own (--drive AXIS=SPEC)");
    }
    by_axis.insert_or_assign(axis, spec);
  }
  return by_axis;
}

}  // namespace netmc::drive
