#include "server/job/quantity_text.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace netmc::job {
namespace {

[[noreturn]] void fail(std::string_view field, const std::string& message) {
  throw std::invalid_argument(std::string(field) + ": " + message);
}

}  // namespace

std::string_view trim(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

std::string join_list(const std::vector<std::string>& words, const char* separator) {
  std::string text;
  for (const auto& word : words) text += (text.empty() ? "" : separator) + word;
  return text;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item(trim(std::string_view(text).substr(
        start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (!item.empty()) items.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

double parse_quantity(std::string_view text, Quantity quantity, std::string_view field) {
  text = trim(text);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  const std::string_view unit = trim(std::string_view(end, static_cast<std::size_t>(text.data() + text.size() - end)));
  const char* form = quantity == Quantity::length  ? "a length such as 10mm, 0.01 or 250um"
                     : quantity == Quantity::time  ? "a duration such as 5ms, 0.005 or 800us"
                     : quantity == Quantity::speed ? "a speed such as 20mm/s or 0.02"
                     : quantity == Quantity::acceleration ? "an acceleration such as 500mm/s2 or 0.5"
                                                          : "a number";
  if (error != std::errc() || text.empty() || !std::isfinite(value)) {
    fail(field, "expected " + std::string(form) + ", got '" + std::string(text) + "'");
  }
  double scale = 1.0;
  if (unit.empty()) {
    scale = 1.0;
  } else if (quantity == Quantity::length && unit == "m") {
    scale = 1.0;
  } else if (quantity == Quantity::length && unit == "mm") {
    scale = 1e-3;
  } else if (quantity == Quantity::length && unit == "um") {
    scale = 1e-6;
  } else if (quantity == Quantity::time && unit == "s") {
    scale = 1.0;
  } else if (quantity == Quantity::time && unit == "ms") {
    scale = 1e-3;
  } else if (quantity == Quantity::time && unit == "us") {
    scale = 1e-6;
  } else if (quantity == Quantity::speed && unit == "m/s") {
    scale = 1.0;
  } else if (quantity == Quantity::speed && unit == "mm/s") {
    scale = 1e-3;
  } else if (quantity == Quantity::speed && unit == "um/s") {
    scale = 1e-6;
  } else if (quantity == Quantity::acceleration && (unit == "m/s2" || unit == "m/s^2")) {
    scale = 1.0;
  } else if (quantity == Quantity::acceleration && (unit == "mm/s2" || unit == "mm/s^2")) {
    scale = 1e-3;
  } else {
    fail(field, "expected " + std::string(form) + ", got unit '" + std::string(unit) + "'");
  }
  return value * scale;
}

// Parses "a=1,b=2" and checks every key is allowed. The value of a key in `list_keys` may contain
// commas itself ("points=0,0;1mm,0"): the items without '=' that follow it belong to it.
std::map<std::string, std::string> parse_keys(std::string_view text, std::string_view field,
                                              const std::vector<std::string>& allowed,
                                              const std::vector<std::string>& list_keys) {
  std::map<std::string, std::string> keys;
  std::string expected;
  for (const auto& key : allowed) expected += (expected.empty() ? "" : ", ") + key;
  std::size_t start = 0;
  std::string list_key;  // the list-valued key being read
  while (start <= text.size() && !text.empty()) {
    const std::size_t comma = text.find(',', start);
    const std::string_view item =
        trim(text.substr(start, comma == std::string_view::npos ? text.size() - start : comma - start));
    const std::size_t equals = item.find('=');
    if (!item.empty() && equals == std::string_view::npos && !list_key.empty()) {
      std::string& value = keys[list_key];
      value.push_back(',');
      value.append(item);
      if (comma == std::string_view::npos) break;
      start = comma + 1;
      continue;
    }
    if (item.empty() || equals == std::string_view::npos) {
      fail(field, "expected key=value, got '" + std::string(item) + "' (keys: " + expected + ")");
    }
    const std::string key(trim(item.substr(0, equals)));
    bool known = false;
    for (const auto& candidate : allowed) known = known || candidate == key;
    if (!known) fail(field, "unknown key '" + key + "' (expected one of: " + expected + ")");
    if (keys.contains(key)) fail(field, "key '" + key + "' given twice");
    keys[key] = std::string(trim(item.substr(equals + 1)));
    list_key.clear();
    for (const auto& candidate : list_keys) {
      if (candidate == key) list_key = key;
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return keys;
}

}  // namespace netmc::job
