#include "server/job/controller_gains.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

#include "server/job/quantity_text.hpp"

namespace netmc::job {
namespace {

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw std::invalid_argument(field + ": " + message);
}

std::string key_names(const GainGroup& group) {
  std::vector<std::string> names;
  for (const auto& key : group.keys) names.push_back(key.name);
  return join_list(names);
}

const char* check_form(GainCheck check) {
  switch (check) {
    case GainCheck::finite: return "a finite number";
    case GainCheck::positive: return "a positive finite number";
    case GainCheck::non_negative: return "a finite number >= 0";
    case GainCheck::whole: return "a whole number >= 0 (at most 1e6)";
  }
  return "a number";
}

bool passes(GainCheck check, double value) {
  if (!std::isfinite(value)) return false;
  switch (check) {
    case GainCheck::finite: return true;
    case GainCheck::positive: return value > 0.0;
    case GainCheck::non_negative: return value >= 0.0;
    case GainCheck::whole: return value >= 0.0 && value <= 1e6 && value == std::floor(value);
  }
  return false;
}

// One set of values, choices and lists (a group's, or an axis's own) against the group's keys.
template <class Set>
void check_set(const Set& set, const GainGroup& group, const std::string& path) {
  const auto known = [&](const std::string& name, GainKey::Kind kind, const char* what) -> const GainKey& {
    const GainKey* key = group.key(name);
    if (!key) fail(path + "." + name.substr(0, 64), "unknown key (expected one of: " + key_names(group) + ")");
    if (key->kind != kind) fail(path + "." + name, std::string("is not ") + what);
    return *key;
  };
  for (const auto& [name, value] : set.values()) {
    const GainKey& key = known(name, GainKey::Kind::number, "a number");
    if (!passes(key.check, value)) fail(path + "." + name, fmt::format("expected {}, got {:g}", check_form(key.check), value));
  }
  for (const auto& [name, choice] : set.choices()) {
    const GainKey& key = known(name, GainKey::Kind::choice, "a choice");
    if (std::find(key.choices.begin(), key.choices.end(), choice) == key.choices.end()) {
      fail(path + "." + name, "expected " + join_list(key.choices, " or ") + ", got '" + choice.substr(0, 64) + "'");
    }
  }
  for (const auto& [name, list] : set.lists()) {
    const GainKey& key = known(name, GainKey::Kind::list, "a list");
    if (static_cast<std::size_t>(list.values_size()) != key.list_size) {
      fail(path + "." + name, fmt::format("expected {} numbers, got {}", key.list_size, list.values_size()));
    }
    for (const double value : list.values()) {
      if (!passes(key.check, value)) fail(path + "." + name, fmt::format("expected {}s, got {:g}", check_form(key.check), value));
    }
  }
}

// A flag value of `key`: a number (with the key's units), a word of its choices, or a list "a;b;c".
void set_from_text(const GainKey& key, const std::string& text, const std::string& field, netmc::v1::AxisGains& out) {
  switch (key.kind) {
    case GainKey::Kind::number: {
      const double value = parse_quantity(text, key.quantity, field);
      if (!passes(key.check, value)) fail(field, "expected " + std::string(check_form(key.check)) + ", got '" + text + "'");
      (*out.mutable_values())[key.name] = value;
      return;
    }
    case GainKey::Kind::choice:
      if (std::find(key.choices.begin(), key.choices.end(), text) == key.choices.end()) {
        fail(field, "expected " + join_list(key.choices, " or ") + ", got '" + text.substr(0, 64) + "'");
      }
      (*out.mutable_choices())[key.name] = text;
      return;
    case GainKey::Kind::list: {
      netmc::v1::NumberList list;
      std::size_t start = 0;
      while (start <= text.size()) {
        const std::size_t semicolon = std::min(text.find(';', start), text.size());
        list.add_values(parse_quantity(text.substr(start, semicolon - start), key.quantity, field));
        start = semicolon + 1;
      }
      if (static_cast<std::size_t>(list.values_size()) != key.list_size) {
        fail(field, fmt::format("expected {} numbers separated by ';', got {}", key.list_size, list.values_size()));
      }
      (*out.mutable_lists())[key.name] = list;
      return;
    }
  }
}

template <class Set>
void merge_into(const netmc::v1::AxisGains& from, Set& into) {
  for (const auto& [name, value] : from.values()) (*into.mutable_values())[name] = value;
  for (const auto& [name, choice] : from.choices()) (*into.mutable_choices())[name] = choice;
  for (const auto& [name, list] : from.lists()) (*into.mutable_lists())[name] = list;
}

}  // namespace

const GainKey* GainGroup::key(std::string_view wanted) const {
  for (const auto& candidate : keys) {
    if (candidate.name == wanted) return &candidate;
  }
  return nullptr;
}

std::string GainGroup::syntax() const {
  std::string text;
  for (const auto& key : keys) {
    const std::string shown = key.flag_aliases.empty() ? key.name : key.flag_aliases.front();
    if (text.find(shown + "=") != std::string::npos) continue;  // an alias of two keys, once
    text += (text.empty() ? "" : ",") + shown + "=";
    if (key.kind == GainKey::Kind::choice) {
      text += join_list(key.choices, "|");
    } else if (key.kind == GainKey::Kind::list) {
      text += fmt::format("{} numbers;..", key.list_size);
    } else {
      text += "..";
    }
  }
  return text + (per_axis ? " (AXIS.KEY=.. for one axis)" : "");
}

void check_gains(const netmc::v1::ControllerSpec& spec, const std::vector<const GainGroup*>& groups,
                 const std::vector<std::string>& axis_names) {
  for (const auto& [name, gains] : spec.gains()) {
    const std::string path = "controller.gains." + name.substr(0, 64);
    const auto found = std::find_if(groups.begin(), groups.end(), [&](const GainGroup* g) { return g->name == name; });
    if (found == groups.end()) {
      std::vector<std::string> names;
      for (const auto* g : groups) names.push_back(g->name);
      fail(path, "no such gains group (expected one of: " + join_list(names) + ")");
    }
    const GainGroup& group = **found;
    check_set(gains, group, path);
    for (const auto& [axis, own] : gains.axes()) {
      if (!group.per_axis) fail(path + ".axes", "the group takes no per-axis values");
      if (std::find(axis_names.begin(), axis_names.end(), axis) == axis_names.end()) {
        fail(path + ".axes." + axis.substr(0, 64), "not an axis of the job (expected one of: " + join_list(axis_names) + ")");
      }
      check_set(own, group, path + ".axes." + axis);
    }
  }
}

GainsReader::GainsReader(const netmc::v1::ControllerSpec& spec, std::vector<std::string> axis_names)
    : spec_(spec), axis_names_(std::move(axis_names)) {}

const netmc::v1::Gains* GainsReader::group(std::string_view name) const {
  const auto it = spec_.gains().find(std::string(name));
  return it == spec_.gains().end() ? nullptr : &it->second;
}

const netmc::v1::AxisGains* GainsReader::axis_gains(std::string_view name, std::size_t axis) const {
  const auto* gains = group(name);
  if (!gains || axis >= axis_names_.size()) return nullptr;
  const auto it = gains->axes().find(axis_names_[axis]);
  return it == gains->axes().end() ? nullptr : &it->second;
}

bool GainsReader::has_axis_values(std::string_view name, std::size_t axis) const {
  return axis_gains(name, axis) != nullptr;
}

bool GainsReader::read(std::string_view name, std::string_view key, std::size_t axis, double& target) const {
  const std::string wanted(key);
  if (const auto* own = axis_gains(name, axis)) {
    if (const auto it = own->values().find(wanted); it != own->values().end()) {
      target = it->second;
      return true;
    }
  }
  const auto* gains = group(name);
  if (!gains) return false;
  const auto it = gains->values().find(wanted);
  if (it == gains->values().end()) return false;
  target = it->second;
  return true;
}

std::optional<std::string> GainsReader::choice(std::string_view name, std::string_view key, std::size_t axis) const {
  const std::string wanted(key);
  if (const auto* own = axis_gains(name, axis)) {
    if (const auto it = own->choices().find(wanted); it != own->choices().end()) return it->second;
  }
  const auto* gains = group(name);
  if (!gains) return std::nullopt;
  const auto it = gains->choices().find(wanted);
  if (it == gains->choices().end()) return std::nullopt;
  return it->second;
}

std::optional<std::vector<double>> GainsReader::list(std::string_view name, std::string_view key,
                                                     std::size_t axis) const {
  const std::string wanted(key);
  const netmc::v1::NumberList* found = nullptr;
  if (const auto* own = axis_gains(name, axis)) {
    if (const auto it = own->lists().find(wanted); it != own->lists().end()) found = &it->second;
  }
  if (!found) {
    const auto* gains = group(name);
    if (!gains) return std::nullopt;
    const auto it = gains->lists().find(wanted);
    if (it == gains->lists().end()) return std::nullopt;
    found = &it->second;
  }
  return std::vector<double>(found->values().begin(), found->values().end());
}

std::string GainsReader::field(std::string_view name, std::string_view key, std::size_t axis) const {
  std::string path = "controller.gains." + std::string(name);
  if (axis_gains(name, axis)) path += ".axes." + axis_names_[axis];
  return path + "." + std::string(key);
}

void set_gain(netmc::v1::ControllerSpec& spec, const std::string& group, const std::string& key, double value) {
  (*(*spec.mutable_gains())[group].mutable_values())[key] = value;
}

void set_axis_gain(netmc::v1::ControllerSpec& spec, const std::string& group, const std::string& axis,
                   const std::string& key, double value) {
  (*(*(*spec.mutable_gains())[group].mutable_axes())[axis].mutable_values())[key] = value;
}

void set_gain_choice(netmc::v1::ControllerSpec& spec, const std::string& group, const std::string& key,
                     const std::string& choice) {
  (*(*spec.mutable_gains())[group].mutable_choices())[key] = choice;
}

void parse_gain_flag(std::string_view text, const GainGroup& group, const std::vector<std::string>& axis_names,
                     netmc::v1::ControllerSpec& spec) {
  netmc::v1::AxisGains common;
  std::map<std::string, netmc::v1::AxisGains> own;
  std::set<std::pair<std::string, std::string>> given;  // (axis, key): each once ("wo" sets woc and wom)
  for (const auto& item : split_list(std::string(text))) {
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos || equals == 0) {
      fail(group.flag, "expected KEY=VALUE entries (" + group.syntax() + "), got '" + item.substr(0, 80) + "'");
    }
    std::string target = std::string(trim(std::string_view(item).substr(0, equals)));
    const std::string value = std::string(trim(std::string_view(item).substr(equals + 1)));
    std::string axis;
    // AXIS.KEY: the longest axis name that prefixes the target (axis names may contain dots).
    for (const auto& name : axis_names) {
      if (target.size() > name.size() + 1 && target.compare(0, name.size(), name) == 0 && target[name.size()] == '.' &&
          name.size() > axis.size()) {
        axis = name;
      }
    }
    if (!axis.empty()) {
      if (!group.per_axis) fail(group.flag, "takes no per-axis values (" + target.substr(0, 64) + ")");
      target = target.substr(axis.size() + 1);
    }
    std::vector<const GainKey*> keys;
    for (const auto& key : group.keys) {
      if (key.name == target || std::find(key.flag_aliases.begin(), key.flag_aliases.end(), target) != key.flag_aliases.end()) {
        keys.push_back(&key);
      }
    }
    if (keys.empty()) {
      std::vector<std::string> names;
      for (const auto& key : group.keys) names.push_back(key.flag_aliases.empty() ? key.name : key.flag_aliases.front());
      fail(group.flag, "unknown key '" + target.substr(0, 64) + "' (expected one of: " + join_list(names) +
                           (group.per_axis ? ", or AXIS.KEY with AXIS one of " + join_list(axis_names) : std::string()) + ")");
    }
    for (const GainKey* key : keys) {
      if (!given.emplace(axis, key->name).second) {
        fail(group.flag, (axis.empty() ? std::string() : axis + ".") + key->name + " is given twice (by '" +
                             target.substr(0, 64) + "' and an earlier entry)");
      }
      set_from_text(*key, value, group.flag + " " + target, axis.empty() ? common : own[axis]);
    }
  }
  auto& gains = (*spec.mutable_gains())[group.name];
  merge_into(common, gains);
  for (const auto& [axis, values] : own) merge_into(values, (*gains.mutable_axes())[axis]);
}

}  // namespace netmc::job
