// Reading of delay traces from CSV files and from `ping -D` output; the formats are documented at
// load_delay_trace_csv and load_delay_trace in delay_model.hpp.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "netsim/delay_model.hpp"
#include "netsim/parameter_check.hpp"

namespace netmc::netsim {

namespace {

constexpr std::uintmax_t kMaxDelayTraceBytes = std::uintmax_t{64} << 20;

std::string_view trim(std::string_view text) {
  constexpr std::string_view whitespace = " \t\r\n";  // '\r' so CRLF files work too
  const auto first = text.find_first_not_of(whitespace);
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(whitespace);
  return text.substr(first, last - first + 1);
}

std::string_view last_column(std::string_view line) {
  const auto comma = line.rfind(',');
  return trim(comma == std::string_view::npos ? line : line.substr(comma + 1));
}

// Locale-independent parse of the whole token; nullopt if it is not a number.
// Out-of-range magnitudes come back as +inf so the finiteness check reports them.
std::optional<double> parse_number(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (end != token.data() + token.size()) return std::nullopt;
  if (error == std::errc::result_out_of_range) return std::numeric_limits<double>::infinity();
  if (error != std::errc()) return std::nullopt;
  return value;
}

// Seconds per unit named by a header column's suffix; seconds when there is no known suffix.
double unit_from_header(std::string_view column_name) {
  std::string name;
  for (const char c : column_name) {
    if (c != '"') name.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  const std::string_view unit_name = trim(name);
  if (unit_name.ends_with("_ms")) return 1e-3;
  if (unit_name.ends_with("_us")) return 1e-6;
  return 1.0;
}

[[noreturn]] void fail(const std::string& path, std::size_t line_number, const std::string& problem,
                       const char* kind = "CSV") {
  throw std::invalid_argument(std::string("delay trace ") + kind + " " + path + ":" + std::to_string(line_number) +
                              ": " + problem);
}

// A regular file of bounded size: not a device (/dev/zero never ends a line), FIFO or directory.
void check_trace_file(const std::string& path, const char* kind) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) {
    throw std::invalid_argument(std::string("delay trace ") + kind + " " + path +
                                ": cannot open the file for reading (no such file)");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw std::invalid_argument(std::string("delay trace ") + kind + " " + path +
                                ": not a regular file (a device, FIFO or directory)");
  }
  const auto size = std::filesystem::file_size(path, error);
  if (error || size > kMaxDelayTraceBytes) {
    throw std::invalid_argument(std::string("delay trace ") + kind + " " + path + ": larger than " +
                                std::to_string(kMaxDelayTraceBytes >> 20) + " MiB");
  }
}

// ping's reply lines: "[1732780000.123456] 64 bytes from 10.0.0.2: icmp_seq=1 ttl=64 time=0.045 ms"
// (the time stamp with -D). The round trip follows "time=", in ms.
constexpr std::string_view kRoundTripKey = "time=";

bool is_ping_output(const std::string& path) {
  std::ifstream file(path);
  std::string line;
  while (std::getline(file, line)) {
    const std::string_view text = trim(line);
    if (text.empty() || text.front() == '#') continue;
    // The first line ping prints, or a reply line.
    return text.starts_with("PING ") ||
           (text.find(" bytes from ") != std::string_view::npos && text.find(kRoundTripKey) != std::string_view::npos);
  }
  return false;
}

}  // namespace

std::vector<double> load_delay_trace(const std::string& path, double round_trip_share) {
  if (!(std::isfinite(round_trip_share) && round_trip_share > 0.0 && round_trip_share <= 1.0)) {
    throw std::invalid_argument("delay trace " + path + ": the round trip's share must be in (0, 1] (got " +
                                std::to_string(round_trip_share) + ")");
  }
  check_trace_file(path, "file");
  if (!is_ping_output(path)) return load_delay_trace_csv(path);
  std::ifstream file(path);
  if (!file) throw std::invalid_argument("delay trace ping output " + path + ": cannot open the file for reading");
  std::vector<double> delays_s;
  std::size_t line_number = 0;
  std::string line;
  while (std::getline(file, line)) {
    ++line_number;
    const std::string_view text = trim(line);
    const auto key = text.find(kRoundTripKey);
    // Headers, statistics, timeouts and errors carry no round trip: a lost probe is no delay.
    if (key == std::string_view::npos || text.find(" bytes from ") == std::string_view::npos) continue;
    std::string_view rest = text.substr(key + kRoundTripKey.size());
    const auto space = rest.find(' ');
    const std::string_view number = rest.substr(0, space);
    const std::string_view unit = space == std::string_view::npos ? std::string_view{} : trim(rest.substr(space));
    const std::optional<double> round_trip = parse_number(number);
    if (!round_trip || !unit.starts_with("ms")) {
      fail(path, line_number, "expected 'time=NUMBER ms' (got '" + std::string(rest.substr(0, 40)) + "')",
           "ping output");
    }
    const double delay_s = *round_trip * 1e-3 * round_trip_share;
    if (!(std::isfinite(delay_s) && delay_s >= 0.0 && delay_s <= kMaxDelayS)) {
      fail(path, line_number, "delay must be a number in [0, 60] s (got time=" + std::string(number) + " ms)",
           "ping output");
    }
    if (delays_s.size() == kMaxDelayTraceSamples) {
      fail(path, line_number, "more than " + std::to_string(kMaxDelayTraceSamples) + " delay samples", "ping output");
    }
    delays_s.push_back(delay_s);
  }
  if (file.bad()) fail(path, line_number, "read error", "ping output");
  if (delays_s.empty()) {
    fail(path, line_number + 1, "no replies ('bytes from ... time=NUMBER ms') before end of file", "ping output");
  }
  return delays_s;
}

std::vector<double> load_delay_trace_csv(const std::string& path) {
  check_trace_file(path, "CSV");
  std::ifstream file(path);
  if (!file) {
    throw std::invalid_argument("delay trace CSV " + path + ": cannot open the file for reading");
  }
  std::vector<double> delays_s;
  double seconds_per_unit = 1.0;
  bool header_possible = true;
  std::size_t line_number = 0;
  std::string line;
  while (std::getline(file, line)) {
    ++line_number;
    const std::string_view text = trim(line);
    if (text.empty() || text.front() == '#') continue;
    const std::string_view token = last_column(text);
    const std::optional<double> value = parse_number(token);
    if (header_possible) {
      header_possible = false;
      if (!value) {
        seconds_per_unit = unit_from_header(token);
        continue;
      }
    }
    if (!value) {
      fail(path, line_number,
           "last column must be a delay number (got '" + std::string(token) + "'; a header is only allowed "
           "as the first non-comment line)");
    }
    if (!(std::isfinite(*value) && *value >= 0.0 && *value * seconds_per_unit <= kMaxDelayS)) {
      fail(path, line_number, "delay must be a number in [0, 60] s (got '" + std::string(token) + "')");
    }
    if (delays_s.size() == kMaxDelayTraceSamples) {
      fail(path, line_number, "more than " + std::to_string(kMaxDelayTraceSamples) + " delay samples");
    }
    delays_s.push_back(*value * seconds_per_unit);
  }
  if (file.bad()) fail(path, line_number, "read error");
  if (delays_s.empty()) {
    fail(path, line_number + 1,
         "no delay samples before end of file (expected lines whose last comma-separated column is a delay)");
  }
  return delays_s;
}

}  // namespace netmc::netsim
