#include "server/drive/modbus/modbus_tcp_spec.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "server/drive/modbus/duration_text.hpp"

namespace netmc::drive::modbus {
namespace {

constexpr std::size_t kMaxSpecLength = 4096;
constexpr std::size_t kMaxHostLength = 253;  // a DNS name's limit

bool all_digits(const std::string& text, std::size_t max_length) {
  return !text.empty() && text.size() <= max_length && text.find_first_not_of("0123456789") == std::string::npos;
}

bool host_name(const std::string& text) {
  return !text.empty() && text.size() <= kMaxHostLength && text.front() != '-' && text.front() != '.' &&
         text.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789.-") == std::string::npos;
}

std::string quoted_excerpt(const std::string& text) { return "'" + text.substr(0, 80) + (text.size() > 80 ? "...'" : "'"); }

}  // namespace

ModbusTcpSpec parse_modbus_tcp_spec(const std::string& text) {
  const std::string where = "modbus-tcp:" + text.substr(0, 80) + (text.size() > 80 ? "..." : "");
  const auto fail = [&](const std::string& field, const std::string& problem) {
    return std::invalid_argument(where + ": " + field + ": " + problem);
  };
  if (text.size() > kMaxSpecLength ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7f; })) {
    throw std::invalid_argument("modbus-tcp: expected HOST:PORT[,unit=N][,map=FILE][,timeout=DURATION], printable, "
                                "at most 4096 characters");
  }
  const std::size_t comma = text.find(',');
  const std::string address = text.substr(0, comma);
  const std::size_t colon = address.rfind(':');
  if (colon == std::string::npos) {
    throw fail("address", "expected HOST:PORT[,unit=N][,map=FILE][,timeout=DURATION], got " + quoted_excerpt(address));
  }
  ModbusTcpSpec spec;
  spec.host = address.substr(0, colon);
  if (!host_name(spec.host)) {
    throw fail("host", "expected an IPv4 address or a host name (letters, digits, '.', '-'), got " + quoted_excerpt(spec.host));
  }
  const std::string port = address.substr(colon + 1);
  if (!all_digits(port, 5) || std::stoi(port) < 1 || std::stoi(port) > 65535) {
    throw fail("port", "expected 1..65535, got " + quoted_excerpt(port));
  }
  spec.port = static_cast<std::uint16_t>(std::stoi(port));
  std::set<std::string> given;
  std::size_t start = comma;
  while (start != std::string::npos) {
    const std::size_t next = text.find(',', start + 1);
    const std::string item = text.substr(start + 1, next == std::string::npos ? std::string::npos : next - start - 1);
    start = next;
    const std::size_t equals = item.find('=');
    const std::string key = item.substr(0, equals);
    if (equals == std::string::npos || (key != "unit" && key != "map" && key != "timeout")) {
      throw fail(quoted_excerpt(item), "expected unit=N, map=FILE or timeout=DURATION");
    }
    if (!given.insert(key).second) throw fail(key, "given twice");
    const std::string value = item.substr(equals + 1);
    if (key == "unit") {
      if (!all_digits(value, 3) || std::stoi(value) > 255) throw fail("unit", "expected 0..255, got " + quoted_excerpt(value));
      spec.unit = static_cast<std::uint8_t>(std::stoi(value));
    } else if (key == "map") {
      if (value.empty()) throw fail("map", "expected the path of a register map file");
      spec.map_path = value;
    } else {
      const double seconds = parse_duration_s(value, where + ": timeout");
      if (!(seconds >= 1e-3 && seconds <= 10.0)) throw fail("timeout", "expected 1ms..10s, got " + quoted_excerpt(value));
      spec.timeout_s = seconds;
    }
  }
  return spec;
}

}  // namespace netmc::drive::modbus
