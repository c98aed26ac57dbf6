#include "server/plugins/component_plugin_spec.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace netmc::plugins {
namespace {

bool key_character(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '-';
}

bool decimal_character(char c) { return (c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-'; }

bool printable(char c) { return c >= 0x20 && c <= 0x7E; }

// The operator's text in a message: quoted, cut short when long, unprintable bytes as '?'.
std::string quoted(std::string_view text) {
  constexpr std::size_t kShown = 80;
  std::string shown(text.substr(0, kShown));
  std::replace_if(shown.begin(), shown.end(), [](char c) { return !printable(c); }, '?');
  return "'" + shown + (text.size() > kShown ? "...'" : "'");
}

[[noreturn]] void refuse(const std::string& why) { throw std::invalid_argument("plugin: " + why); }

std::pair<std::string, double> parse_setting(std::string_view item) {
  if (item.empty()) refuse("an empty key=value item (two commas, or a comma at an end)");
  const std::size_t equals = item.find('=');
  if (equals == std::string_view::npos) refuse(quoted(item) + " has no '=' (settings are key=value)");
  const std::string_view key = item.substr(0, equals);
  if (key.empty()) refuse(quoted(item) + " has no key before '='");
  if (key.size() > kMaxComponentPluginKeyLength) {
    refuse("key " + quoted(key) + " is longer than " + std::to_string(kMaxComponentPluginKeyLength) + " characters");
  }
  if (!is_component_plugin_key(key)) refuse("key " + quoted(key) + " has a character other than A-Z a-z 0-9 _ . -");
  return {std::string(key), parse_component_plugin_value(key, item.substr(equals + 1))};
}

}  // namespace

bool is_component_plugin_key(std::string_view key) {
  return !key.empty() && key.size() <= kMaxComponentPluginKeyLength && std::all_of(key.begin(), key.end(), key_character);
}

double parse_component_plugin_value(std::string_view key, std::string_view text) {
  const std::string name(key.substr(0, kMaxComponentPluginKeyLength));
  if (text.empty()) refuse("key " + name + " has no value (settings are key=number)");
  if (text.size() > kMaxComponentPluginValueLength) {
    refuse("the value of " + name + " is longer than " + std::to_string(kMaxComponentPluginValueLength) + " characters");
  }
  // Decimal only: from_chars alone would also take "inf", "nan" and a hexadecimal mantissa.
  const bool decimal = std::all_of(text.begin(), text.end(), decimal_character);
  std::string_view digits = text;
  if (digits.size() > 1 && digits.front() == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (!decimal || error != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value)) {
    refuse("the value of " + name + ", " + quoted(text) + ", is not a finite decimal number");
  }
  return value;
}

ComponentPluginSpec parse_component_plugin_spec(const std::string& text) {
  ComponentPluginSpec spec;
  const std::size_t colon = text.find(':');
  spec.path = text.substr(0, colon);
  if (spec.path.empty()) refuse("no path to the plugin (plugin:PATH.so[:key=value,...])");
  if (spec.path.size() > kMaxComponentPluginPathLength) {
    refuse("the path is longer than " + std::to_string(kMaxComponentPluginPathLength) + " characters");
  }
  if (!std::all_of(spec.path.begin(), spec.path.end(), printable)) {
    refuse("the path has a character that is not printable ASCII");
  }
  if (spec.path.find(',') != std::string::npos) {
    refuse("the path " + quoted(spec.path) + " has a ',' (a plugin's path may hold neither ':' nor ',')");
  }
  if (colon == std::string::npos) return spec;

  const std::string_view settings = std::string_view(text).substr(colon + 1);
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = settings.find(',', begin);
    if (spec.settings.size() == kMaxComponentPluginSettings) {
      refuse("more than " + std::to_string(kMaxComponentPluginSettings) + " key=value settings");
    }
    auto [key, value] =
        parse_setting(settings.substr(begin, comma == std::string_view::npos ? comma : comma - begin));
    if (!spec.settings.emplace(key, value).second) refuse("key " + key + " given twice");
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  return spec;
}

}  // namespace netmc::plugins
