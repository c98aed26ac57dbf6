#include "server/drive/plugin/plugin_spec.hpp"

#include <algorithm>
#include <stdexcept>

namespace netmc::drive {
namespace {

bool key_character(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '-';
}

bool printable(char c) { return c >= 0x20 && c <= 0x7E; }

// Shown in messages: the operator's text, cut short if it is long.
std::string quoted(const std::string& text) {
  constexpr std::size_t kShown = 80;
  return "'" + (text.size() > kShown ? text.substr(0, kShown) + "..." : text) + "'";
}

[[noreturn]] void refuse(const std::string& why) { throw std::invalid_argument("--drive plugin: " + why); }

std::pair<std::string, std::string> parse_setting(const std::string& item) {
  if (item.empty()) refuse("an empty key=value item (two commas, or a comma at an end)");
  const std::size_t equals = item.find('=');
  if (equals == std::string::npos) refuse(quoted(item) + " has no '=' (settings are key=value)");
  std::string key = item.substr(0, equals);
  std::string value = item.substr(equals + 1);
  if (key.empty()) refuse(quoted(item) + " has no key before '='");
  if (key.size() > kMaxPluginKeyLength) {
    refuse("key " + quoted(key) + " is longer than " + std::to_string(kMaxPluginKeyLength) + " characters");
  }
  if (!std::all_of(key.begin(), key.end(), key_character)) {
    refuse("key " + quoted(key) + " has a character other than A-Z a-z 0-9 _ . -");
  }
  if (value.size() > kMaxPluginValueLength) {
    refuse("the value of " + key + " is longer than " + std::to_string(kMaxPluginValueLength) + " characters");
  }
  if (!std::all_of(value.begin(), value.end(), printable)) {
    refuse("the value of " + key + " has a character that is not printable ASCII");
  }
  return {std::move(key), std::move(value)};
}

}  // namespace

PluginSpec parse_plugin_spec(const std::string& text) {
  PluginSpec spec;
  const std::size_t colon = text.find(':');
  spec.path = text.substr(0, colon);
  if (spec.path.empty()) refuse("no path to the plugin (plugin:PATH.so[:key=value,...])");
  if (spec.path.size() > kMaxPluginPathLength) {
    refuse("the path is longer than " + std::to_string(kMaxPluginPathLength) + " characters");
  }
  if (!std::all_of(spec.path.begin(), spec.path.end(), printable)) {
    refuse("the path has a character that is not printable ASCII");
  }
  if (colon == std::string::npos) return spec;

  const std::string settings = text.substr(colon + 1);
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = settings.find(',', begin);
    if (spec.settings.size() == kMaxPluginSettings) {
      refuse("more than " + std::to_string(kMaxPluginSettings) + " key=value settings");
    }
    auto setting = parse_setting(settings.substr(begin, comma == std::string::npos ? comma : comma - begin));
    for (const auto& [key, value] : spec.settings) {
      if (key == setting.first) refuse("key " + key + " given twice");
    }
    spec.settings.push_back(std::move(setting));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return spec;
}

}  // namespace netmc::drive
