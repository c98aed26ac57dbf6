#include "server/drive/modbus/modbus_map_file.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <functional>
#include <set>
#include <stdexcept>
#include <vector>

namespace netmc::drive::modbus {
namespace {

using nlohmann::json;

constexpr int kMaxDepth = 8;  // the schema nests three deep
constexpr std::size_t kMaxDescription = 1024;

// A JSON value shown in a message: short, escaped.
std::string shown(const json& value) {
  std::string text = value.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

// A key from the file in a message: printable ASCII, at most 40 characters.
std::string printable(const std::string& key) {
  std::string out;
  for (const char c : key.substr(0, 40)) out += c >= 0x20 && c < 0x7f ? c : '?';
  return key.size() > 40 ? out + "..." : out;
}

// Remembers what nlohmann's parser lets pass: a key given twice in one object (it keeps the
// last) and nesting beyond the schema's.
class KeyChecker {
 public:
  bool operator()(int depth, json::parse_event_t event, json& parsed) {
    if (depth > kMaxDepth && problem_.empty()) problem_ = fmt::format("nested deeper than {} levels", kMaxDepth);
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        path_.push_back(pending_key_);
        seen_.emplace_back();
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!path_.empty()) path_.pop_back();
        if (!seen_.empty()) seen_.pop_back();
        break;
      case json::parse_event_t::key: {
        pending_key_ = parsed.get<std::string>();
        if (!seen_.empty() && !seen_.back().insert(pending_key_).second && problem_.empty()) {
          problem_ = here() + printable(pending_key_) + ": given twice";
        }
        break;
      }
      case json::parse_event_t::value: break;
    }
    return true;
  }
  const std::string& problem() const { return problem_; }

 private:
  std::string here() const {
    std::string out;
    for (std::size_t i = 1; i < path_.size(); ++i) out += path_[i] + ".";
    return out;
  }
  std::vector<std::string> path_;
  std::vector<std::set<std::string>> seen_;
  std::string pending_key_;
  std::string problem_;
};

class MapReader {
 public:
  explicit MapReader(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw std::invalid_argument(origin_ + ": " + path + ": " + problem);
  }

  void only_keys(const json& object, const std::string& path, const std::vector<std::string>& keys) const {
    for (const auto& [key, value] : object.items()) {
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
        std::string expected;
        for (const auto& k : keys) expected += (expected.empty() ? "" : ", ") + k;
        fail(path.empty() ? printable(key) : path + "." + printable(key), "unknown key (expected one of: " + expected + ")");
      }
    }
  }

  const json& member(const json& object, const std::string& key, const std::string& path,
                     const std::string& expected) const {
    const auto it = object.find(key);
    if (it == object.end()) fail(path.empty() ? key : path + "." + key, "missing (expected " + expected + ")");
    return *it;
  }

  std::int64_t integer(const json& value, const std::string& path, std::int64_t min, std::int64_t max,
                       const std::string& expected) const {
    if (value.is_number_unsigned()) {
      const auto n = value.get<std::uint64_t>();
      if (n <= static_cast<std::uint64_t>(max) && static_cast<std::int64_t>(n) >= min) return static_cast<std::int64_t>(n);
    } else if (value.is_number_integer()) {
      const auto n = value.get<std::int64_t>();
      if (n >= min && n <= max) return n;
    }
    fail(path, "expected " + expected + ", got " + shown(value));
  }

  double number(const json& value, const std::string& path, const std::string& expected) const {
    if (!value.is_number()) fail(path, "expected " + expected + ", got " + shown(value));
    return value.get<double>();
  }

  RegisterPlacement placement(const DriveObjectInfo& info, const json& entry) const {
    const std::string path = std::string("registers.") + info.key;
    if (!entry.is_object()) fail(path, "expected {\"address\": N, \"type\": T" + std::string(info.scale_unit ? ", \"scale\": S" : "") + "}");
    if (info.scale_unit) {
      only_keys(entry, path, {"address", "type", "scale"});
    } else {
      for (const auto& [key, value] : entry.items()) {
        if (key == "scale") fail(path + ".scale", "takes no scale (a CiA 402 word or mode)");
      }
      only_keys(entry, path, {"address", "type"});
    }
    RegisterPlacement out;
    out.address = static_cast<std::uint16_t>(
        integer(member(entry, "address", path, "a register address 0..65535"), path + ".address", 0, 65535,
                "a register address 0..65535"));
    const json& type = member(entry, "type", path, "\"uint16\", \"int16\", \"uint32\" or \"int32\"");
    const auto parsed = type.is_string() ? register_type_from_name(type.get<std::string>()) : std::nullopt;
    if (!parsed) fail(path + ".type", "expected \"uint16\", \"int16\", \"uint32\" or \"int32\", got " + shown(type));
    out.type = *parsed;
    if (info.scale_unit) {
      const std::string expected = fmt::format("a finite non-zero number ({})", info.scale_unit);
      out.scale = number(member(entry, "scale", path, expected), path + ".scale", expected);
    }
    return out;
  }

  void limits(const json& object, ModbusMap& map) const {
    if (!object.is_object()) fail("limits", "expected an object of command, position_window_m, velocity_m_s, slew_per_s");
    only_keys(object, "limits", {"command", "position_window_m", "velocity_m_s", "slew_per_s"});
    if (object.contains("command")) {
      map.limits.command = number(object["command"], "limits.command", "a positive number (the plant's input unit)");
    }
    if (object.contains("velocity_m_s")) {
      map.limits.velocity_m_s = number(object["velocity_m_s"], "limits.velocity_m_s", "a positive number (m/s)");
    }
    if (object.contains("slew_per_s")) {
      map.limits.slew_per_s =
          number(object["slew_per_s"], "limits.slew_per_s", "a positive number (the plant's input unit per second)");
    }
    if (object.contains("position_window_m")) {
      const json& window = object["position_window_m"];
      const std::string expected = "[MIN, MAX] in metres with MIN < MAX";
      if (!window.is_array() || window.size() != 2) fail("limits.position_window_m", "expected " + expected);
      map.limits.position_min_m = number(window[0], "limits.position_window_m", expected);
      map.limits.position_max_m = number(window[1], "limits.position_window_m", expected);
    }
  }

  ModbusMap read(const json& root) const {
    if (!root.is_object()) fail("(top level)", "expected a JSON object with \"format\": \"" + std::string(kMapFormat) + "\"");
    only_keys(root, "",
              {"format", "version", "description", "unit_id", "high_word_first", "job_mode", "registers", "limits"});
    const json& format = member(root, "format", "", std::string("\"") + kMapFormat + "\"");
    if (format != kMapFormat) fail("format", std::string("expected \"") + kMapFormat + "\", got " + shown(format));
    integer(member(root, "version", "", "1"), "version", kMapVersion, kMapVersion, std::to_string(kMapVersion));
    if (root.contains("description")) {
      const json& text = root["description"];
      if (!text.is_string() || text.get<std::string>().size() > kMaxDescription) {
        fail("description", fmt::format("expected a string of at most {} characters", kMaxDescription));
      }
    }
    ModbusMap map;
    map.origin = origin_;
    map.registers = {};
    map.unit_id = static_cast<std::uint8_t>(
        integer(member(root, "unit_id", "", "a unit id 0..255"), "unit_id", 0, 255, "a unit id 0..255"));
    const json& order = member(root, "high_word_first", "", "true or false");
    if (!order.is_boolean()) fail("high_word_first", "expected true or false, got " + shown(order));
    map.high_word_first = order.get<bool>();
    const json& mode = member(root, "job_mode", "", "\"cst\", \"csv\" or \"csp\"");
    const auto job_mode = mode.is_string() ? operation_mode_from_name(mode.get<std::string>()) : std::nullopt;
    if (!job_mode) fail("job_mode", "expected \"cst\", \"csv\" or \"csp\", got " + shown(mode));
    map.job_mode = *job_mode;
    const json& registers = member(root, "registers", "", "an object of CiA 402 objects");
    if (!registers.is_object()) fail("registers", "expected an object of CiA 402 objects");
    std::vector<std::string> keys;
    for (const auto& info : drive_objects()) keys.emplace_back(info.key);
    only_keys(registers, "registers", keys);
    for (const auto& info : drive_objects()) {
      if (registers.contains(info.key)) {
        map.registers[static_cast<std::size_t>(info.object)] = placement(info, registers[info.key]);
      }
    }
    if (root.contains("limits")) limits(root["limits"], map);
    map.validate();
    return map;
  }

 private:
  std::string origin_;
};

}  // namespace

ModbusMap parse_modbus_map(std::string_view text, const std::string& origin) {
  if (text.size() > kMaxMapFileBytes) {
    throw std::invalid_argument(fmt::format("{}: larger than {} bytes", origin, kMaxMapFileBytes));
  }
  KeyChecker checker;
  json root;
  try {
    root = json::parse(text, std::ref(checker), /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::exception& error) {
    // nlohmann's text names the byte and what it expected ("syntax error while parsing object"),
    // or the number it could not hold ("number overflow parsing '1e400'").
    throw std::invalid_argument(origin + ": not valid JSON: " + error.what());
  }
  if (!checker.problem().empty()) throw std::invalid_argument(origin + ": " + checker.problem());
  return MapReader(origin).read(root);
}

ModbusMap load_modbus_map(const std::string& path) {
  const std::string origin = "map file " + path;
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::invalid_argument(origin + ": cannot read it (" + std::strerror(errno) + ")");
  std::string text(kMaxMapFileBytes + 1, '\0');
  file.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(file.gcount()));
  if (file.bad()) throw std::invalid_argument(origin + ": cannot read it");
  return parse_modbus_map(text, origin);
}

}  // namespace netmc::drive::modbus
