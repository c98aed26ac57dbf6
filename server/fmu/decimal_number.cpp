#include "server/fmu/decimal_number.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <system_error>

namespace netmc::plant::fmu {
namespace {

bool digit(char c) { return c >= '0' && c <= '9'; }

// Length of the run of digits at text[from...].
std::size_t digits_at(std::string_view text, std::size_t from) {
  std::size_t n = 0;
  while (from + n < text.size() && digit(text[from + n])) ++n;
  return n;
}

// True when `text` is exactly one decimal number in the grammar of parse_finite_decimal.
bool decimal_syntax(std::string_view text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  const std::size_t whole = digits_at(text, i);
  i += whole;
  std::size_t fraction = 0;
  if (i < text.size() && text[i] == '.') {
    ++i;
    fraction = digits_at(text, i);
    i += fraction;
  }
  if (whole == 0 && fraction == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    const std::size_t exponent = digits_at(text, i);
    if (exponent == 0) return false;
    i += exponent;
  }
  return i == text.size();
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  return text;
}

}  // namespace

std::optional<double> parse_finite_decimal(std::string_view text) {
  // Bounded: no number an option or an attribute needs is longer.
  constexpr std::size_t kMaxLength = 64;
  if (text.size() > kMaxLength || !decimal_syntax(text)) return std::nullopt;
  if (text.front() == '+') text.remove_prefix(1);  // from_chars takes no '+'
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  // Out of range either way (1e999, 1e-999) is refused: no parameter means either.
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<double> parse_xml_double(std::string_view text) {
  text = trimmed(text);
  if (text == "INF") return std::numeric_limits<double>::infinity();
  if (text == "-INF") return -std::numeric_limits<double>::infinity();
  if (text == "NaN") return std::numeric_limits<double>::quiet_NaN();
  return parse_finite_decimal(text);
}

std::optional<unsigned int> parse_xml_unsigned(std::string_view text) {
  text = trimmed(text);
  if (text.empty() || text.size() > 10 || digits_at(text, 0) != text.size()) return std::nullopt;
  std::uint64_t value = 0;
  for (const char c : text) value = value * 10 + static_cast<std::uint64_t>(c - '0');
  if (value > std::numeric_limits<unsigned int>::max()) return std::nullopt;
  return static_cast<unsigned int>(value);
}

std::optional<bool> parse_xml_boolean(std::string_view text) {
  text = trimmed(text);
  if (text == "true" || text == "1") return true;
  if (text == "false" || text == "0") return false;
  return std::nullopt;
}

}  // namespace netmc::plant::fmu
