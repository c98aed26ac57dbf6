#pragma once
// Which pages may use the console: a request is answered only when its Host header names the
// console (a DNS-rebinding page reaches it under the attacker's name) and its Origin header, when
// a browser sends one, is a page of the console itself (a cross-site POST or WebSocket comes with
// the foreign page's origin). Names compared without port, case-insensitively. Loopback names
// and the address the console listens on are the console's own; a lab adds the names it browses
// to (netmc-server --http-allow-host). Pure: no sockets (tests/console).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace netmc::console {

class RequestOriginPolicy {
 public:
  // "*" in `hosts` allows any Host and Origin (behind a proxy that checks them itself).
  explicit RequestOriginPolicy(std::vector<std::string> hosts);
  // localhost, 127.0.0.1, ::1, `bind_address` (unless it is 0.0.0.0 or ::) and `extra`.
  static RequestOriginPolicy loopback_and(const std::string& bind_address, const std::vector<std::string>& extra);

  // Empty when the request may be answered; otherwise the 403's reason, naming the header.
  // `origin`: nullopt when the request has none (curl, Prometheus, a same-origin GET).
  std::optional<std::string> refusal(std::optional<std::string_view> host, std::optional<std::string_view> origin) const;

  // "localhost, 127.0.0.1, ::1" or "any host" (for the log).
  std::string describe() const;

  // The host of a Host header's value ("name", "name:port", "[::1]:port"), lowercase; nullopt
  // when it is not of that form.
  static std::optional<std::string> host_of(std::string_view host_header);

 private:
  bool allowed(const std::string& host) const;
  std::vector<std::string> hosts_;
  bool any_ = false;
};

}  // namespace netmc::console
