#include "server/job/legacy_spec.hpp"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <string_view>

namespace netmc::job {
namespace {

using nlohmann::ordered_json;

// A field's name as the proto's JSON names it either way: "qCutoffHz" -> "q_cutoff_hz".
std::string snake_case(std::string_view name) {
  std::string out;
  for (const char c : name) {
    if (std::isupper(static_cast<unsigned char>(c))) {
      out += '_';
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out;
}

// Where a legacy field's gains go: its group, and for the per-axis copies the axis (by position
// in the job's axes).
struct LegacyField {
  std::string_view field;
  std::string_view group;
  int axis;  // -1: the group's own values
};

constexpr LegacyField legacy_fields[] = {
    {"adrc", "adrc", -1},           {"adrc_y", "adrc", 1},         {"pid", "pid", -1},
    {"pid_y", "pid", 1},            {"pidccc", "pidccc", -1},      {"ilccc", "ilccc", -1},
    {"gtcf_adrc", "gtcf_adrc", -1}, {"task_space", "task_space", -1}, {"mfa_dtsmc", "mfa_dtsmc", -1},
    {"mfa_dtsmc_y", "mfa_dtsmc", 1}, {"mfac", "mfac", -1},          {"mfac_y", "mfac", 1},
    {"ffpid_x", "ffpid", 0},        {"ffpid_y", "ffpid", 1},       {"lpccc", "lpccc", -1},
    {"axis_diarc", "axis_diarc", -1}, {"avsc", "avsc", -1},
};

// One legacy gain into the gains object (the group's or an axis's): numbers to values, words to
// choices, lists to lists; the two booleans of 0.1 become the choices that replaced them.
void move_gain(const std::string& key, const ordered_json& value, ordered_json& target) {
  if (key == "observer_sees_sent_command") {
    if (value.is_boolean() && value.get<bool>()) target["choices"]["observer_input"] = "sent";
    else if (!value.is_boolean()) target["values"][key] = value;  // left for the checks to name
    return;
  }
  if (key == "initialization_filter" || key == "ltcf_rotation") {
    if (value.is_boolean()) {
      if (value.get<bool>()) target["choices"][key] = "on";
    } else {
      target["choices"][key] = value;
    }
    return;
  }
  if (key == "exact_dead_zone" && value.is_object()) {
    for (const auto& [name, number] : value.items()) target["values"][snake_case(name)] = number;
    return;
  }
  if (value.is_string()) {
    // 0.1 wrote "" for an unset word (observer); proto3 JSON also quotes numbers ("1e3").
    const auto text = value.get<std::string>();
    if (text.empty()) return;
    if (key == "observer" || key == "data_model") target["choices"][key] = value;
    else target["values"][key] = value;
    return;
  }
  if (value.is_array()) {
    if (!value.empty()) target["lists"][key]["values"] = value;
    return;
  }
  target["values"][key] = value;
}

}  // namespace

std::string upgrade_legacy_spec_json(const std::string& text) {
  ordered_json spec = ordered_json::parse(text, nullptr, false);
  if (spec.is_discarded() || !spec.is_object()) return text;
  const auto controller_it = spec.find("controller");
  if (controller_it == spec.end() || !controller_it->is_object()) return text;
  ordered_json& controller = *controller_it;

  bool changed = false;
  ordered_json upgraded = ordered_json::object();
  ordered_json gains = ordered_json::object();
  for (const auto& [name, value] : controller.items()) {
    const std::string field = snake_case(name);
    const LegacyField* legacy = nullptr;
    for (const auto& candidate : legacy_fields) {
      if (candidate.field == field) legacy = &candidate;
    }
    if (!legacy || !value.is_object()) {
      upgraded[name] = value;
      continue;
    }
    changed = true;
    ordered_json& group = gains[std::string(legacy->group)];
    if (group.is_null()) group = ordered_json::object();
    ordered_json* target = &group;
    if (legacy->axis >= 0) {
      std::string axis = legacy->axis == 0 ? "x" : "y";
      const auto axes = spec.find("axes");
      if (axes != spec.end() && axes->is_array() && axes->size() > static_cast<std::size_t>(legacy->axis) &&
          (*axes)[static_cast<std::size_t>(legacy->axis)].is_string()) {
        axis = (*axes)[static_cast<std::size_t>(legacy->axis)].get<std::string>();
      }
      target = &group["axes"][axis];
      if (target->is_null()) *target = ordered_json::object();
    }
    for (const auto& [key, gain] : value.items()) move_gain(snake_case(key), gain, *target);
  }
  if (!changed) return text;
  if (controller.contains("gains")) return text;  // both forms at once: the checks refuse the legacy fields
  // 0.1's data-driven laws defaulted to the compact data model; netmc now asks for the form.
  const auto name = controller.find("name");
  if (name != controller.end() && name->is_string()) {
    for (const char* group : {"mfa_dtsmc", "mfac"}) {
      std::string family(group);
      std::replace(family.begin(), family.end(), '_', '-');
      if (name->get<std::string>() != family) continue;
      ordered_json& choices = gains[group]["choices"];
      if (!choices.contains("data_model")) choices["data_model"] = "compact";
    }
  }
  upgraded["gains"] = gains;
  controller = upgraded;
  return spec.dump(2);
}

}  // namespace netmc::job
