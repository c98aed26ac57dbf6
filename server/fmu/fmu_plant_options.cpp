#include "server/fmu/fmu_plant_options.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

#include "server/fmu/decimal_number.hpp"
#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {
namespace {

[[noreturn]] void refuse(const std::string& why) { throw std::invalid_argument("plant fmu: " + why); }

bool name_character(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.' ||
         c == '[' || c == ']';
}

// A key, or a variable named as the value of input=, output=, ...
void check_name(std::string_view name, const std::string& what) {
  if (name.empty()) refuse(what + " is empty");
  if (name.size() > kMaxFmuKeyLength) {
    refuse(what + " " + quoted(name) + " is longer than " + std::to_string(kMaxFmuKeyLength) + " characters");
  }
  if (!std::all_of(name.begin(), name.end(), name_character)) {
    refuse(what + " " + quoted(name) + " has a character other than A-Z a-z 0-9 _ . [ ]");
  }
}

}  // namespace

std::optional<double> parse_fmu_duration(std::string_view text) {
  static constexpr std::array<std::pair<std::string_view, double>, 4> kUnits{
      {{"ns", 1e-9}, {"us", 1e-6}, {"ms", 1e-3}, {"s", 1.0}}};
  for (const auto& [unit, scale] : kUnits) {
    if (text.size() <= unit.size() || text.substr(text.size() - unit.size()) != unit) continue;
    const auto number = parse_finite_decimal(text.substr(0, text.size() - unit.size()));
    if (!number || !(*number > 0.0)) return std::nullopt;
    const double seconds = *number * scale;
    if (!(seconds > 0.0) || !std::isfinite(seconds)) return std::nullopt;
    return seconds;
  }
  return std::nullopt;
}

FmuPlantOptions parse_fmu_plant_options(std::string_view text) {
  if (text.substr(0, 4) == "fmu:") text.remove_prefix(4);
  if (text.size() > kMaxFmuOptionsText) {
    refuse("the text is longer than " + std::to_string(kMaxFmuOptionsText) + " characters");
  }
  FmuPlantOptions out;
  const std::size_t colon = text.find(':');
  const std::string_view path = text.substr(0, colon);
  if (path.empty()) refuse("no path (expected fmu:PATH.fmu[:KEY=VALUE,...])");
  if (path.size() > kMaxFmuPathLength) refuse("the path is longer than " + std::to_string(kMaxFmuPathLength) + " characters");
  if (path.size() < 5 || path.substr(path.size() - 4) != ".fmu") {
    refuse("the path " + quoted(path) + " does not end in .fmu (expected fmu:PATH.fmu[:KEY=VALUE,...]; a path "
           "cannot contain ':')");
  }
  if (path.find('\0') != std::string_view::npos) refuse("the path has a NUL character");
  out.path = std::string(path);
  if (colon == std::string_view::npos) return out;

  std::string_view rest = text.substr(colon + 1);
  if (rest.empty()) refuse("nothing after ':' (expected KEY=VALUE,...)");
  std::set<std::string, std::less<>> seen;
  std::size_t count = 0;
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    if (++count > kMaxFmuOptions) refuse("more than " + std::to_string(kMaxFmuOptions) + " options");
    if (item.empty()) refuse("an empty option (two commas, or a comma at an end)");
    const std::size_t equals = item.find('=');
    if (equals == std::string_view::npos) refuse("option " + quoted(item) + " has no '=' (options are KEY=VALUE)");
    const std::string key(item.substr(0, equals));
    const std::string_view value = item.substr(equals + 1);
    check_name(key, "the key");
    if (!seen.insert(key).second) refuse("option '" + key + "' is given twice");
    const std::string what = "option '" + key + "'";
    if (value.empty()) refuse(what + " has no value");
    if (key == "input" || key == "output" || key == "velocity" || key == "position_start" ||
        key == "velocity_start") {
      check_name(value, what + ": the variable name");
      if (key == "input") out.input = value;
      if (key == "output") out.output = value;
      if (key == "velocity") out.velocity = std::string(value);
      if (key == "position_start") out.position_start = std::string(value);
      if (key == "velocity_start") out.velocity_start = std::string(value);
    } else if (key == "step") {
      out.step_s = parse_fmu_duration(value);
      if (!out.step_s) refuse(what + ": " + quoted(value) + " is not a positive duration such as 1ms, 250us or 0.002s");
    } else {
      const auto number = parse_finite_decimal(value);
      if (!number) refuse(what + ": " + quoted(value) + " is not a finite decimal number");
      out.parameters.push_back({key, *number});
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return out;
}

}  // namespace netmc::plant::fmu
