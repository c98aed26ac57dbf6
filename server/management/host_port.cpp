#include "server/management/host_port.hpp"

#include <stdexcept>

namespace netmc::management {

HostPort parse_host_port(const std::string& text, const std::string& flag, bool port_zero_allowed) {
  const auto bad = [&] { return std::invalid_argument(flag + ": expected HOST:PORT, got '" + text + "'"); };
  const auto colon = text.rfind(':');
  if (colon == std::string::npos) throw bad();
  std::string host = text.substr(0, colon);
  const std::string port = text.substr(colon + 1);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);  // [IPv6]:PORT
  } else if (host.find(':') != std::string::npos) {
    throw bad();  // a bare IPv6 literal is ambiguous
  }
  if (host.empty() || port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos) {
    throw bad();
  }
  const int number = std::stoi(port);
  if (number > 65535 || (number == 0 && !port_zero_allowed)) throw bad();
  return {host, port};
}

}  // namespace netmc::management
