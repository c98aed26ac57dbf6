#pragma once
// HOST:PORT as the management endpoint's flags take it (--server, --listen): HOST a name or an
// IPv4 address, [IPv6]:PORT for IPv6 literals, PORT all digits.

#include <string>

namespace netmc::management {

struct HostPort {
  std::string host;
  std::string port;
};

// Throws std::invalid_argument("FLAG: expected HOST:PORT, got '…'") for anything else (a bare
// IPv6 literal, a port with other characters or out of range: 1-65535, or 0 where
// `port_zero_allowed`, which asks the system for a free port).
HostPort parse_host_port(const std::string& text, const std::string& flag, bool port_zero_allowed = false);

}  // namespace netmc::management
