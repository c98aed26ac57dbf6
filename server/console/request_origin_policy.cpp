#include "server/console/request_origin_policy.hpp"

#include <algorithm>
#include <cctype>

namespace netmc::console {
namespace {

std::string lowercase(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool is_port(std::string_view text) {
  return !text.empty() && text.size() <= 5 &&
         std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

// A header's value as a message may show it: printable ASCII, at most 64 characters.
std::string shown(std::string_view value) {
  std::string out;
  for (const char c : value.substr(0, 64)) out.push_back(c >= 0x20 && c < 0x7f && c != '\'' && c != '"' && c != '\\' ? c : '?');
  return out + (value.size() > 64 ? "..." : "");
}

// An address written in URLs with brackets is compared without them.
std::string unbracketed(std::string host) {
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') return host.substr(1, host.size() - 2);
  return host;
}

}  // namespace

RequestOriginPolicy::RequestOriginPolicy(std::vector<std::string> hosts) {
  for (auto& host : hosts) {
    if (host == "*") any_ = true;
    hosts_.push_back(unbracketed(lowercase(host)));
  }
}

RequestOriginPolicy RequestOriginPolicy::loopback_and(const std::string& bind_address,
                                                      const std::vector<std::string>& extra) {
  std::vector<std::string> hosts{"localhost", "127.0.0.1", "::1"};
  if (!bind_address.empty() && bind_address != "0.0.0.0" && bind_address != "::") hosts.push_back(bind_address);
  hosts.insert(hosts.end(), extra.begin(), extra.end());
  return RequestOriginPolicy(std::move(hosts));
}

std::optional<std::string> RequestOriginPolicy::host_of(std::string_view value) {
  if (value.empty() || value.size() > 255) return std::nullopt;
  std::string_view host = value;
  if (host.front() == '[') {  // [v6] or [v6]:port
    const auto close = host.find(']');
    if (close == std::string_view::npos) return std::nullopt;
    const std::string_view rest = host.substr(close + 1);
    if (!rest.empty() && (rest.front() != ':' || !is_port(rest.substr(1)))) return std::nullopt;
    host = host.substr(1, close - 1);
    if (host.empty() || host.find_first_not_of("0123456789abcdefABCDEF:.") != std::string_view::npos) return std::nullopt;
    return lowercase(host);
  }
  if (const auto colon = host.find(':'); colon != std::string_view::npos) {
    if (!is_port(host.substr(colon + 1))) return std::nullopt;
    host = host.substr(0, colon);
  }
  if (host.empty()) return std::nullopt;
  const bool name_characters = std::all_of(host.begin(), host.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '-' || c == '.' || c == '_';
  });
  if (!name_characters) return std::nullopt;
  return lowercase(host);
}

std::string RequestOriginPolicy::describe() const {
  if (any_) return "any host";
  std::string text;
  for (const auto& host : hosts_) text += (text.empty() ? "" : ", ") + host;
  return text;
}

bool RequestOriginPolicy::allowed(const std::string& host) const {
  return any_ || std::find(hosts_.begin(), hosts_.end(), host) != hosts_.end();
}

std::optional<std::string> RequestOriginPolicy::refusal(std::optional<std::string_view> host_header,
                                                        std::optional<std::string_view> origin) const {
  if (any_) return std::nullopt;
  if (!host_header) return "a request needs a Host header";
  const auto host = host_of(*host_header);
  if (!host) return "Host '" + shown(*host_header) + "' is not a host name or address";
  if (!allowed(*host)) {
    return "Host '" + shown(*host) + "' is not a name of this console (netmc-server --http-allow-host " + shown(*host) +
           " adds it)";
  }
  if (!origin) return std::nullopt;
  // scheme://host[:port], nothing after it; "null" (a sandboxed page, a file) is no origin of ours.
  const std::string_view value = *origin;
  const auto scheme_end = value.find("://");
  const std::string scheme = scheme_end == std::string_view::npos ? "" : lowercase(value.substr(0, scheme_end));
  const auto origin_host =
      scheme == "http" || scheme == "https" ? host_of(value.substr(scheme_end + 3)) : std::optional<std::string>();
  if (!origin_host || !allowed(*origin_host)) {
    return "Origin '" + shown(value) + "' is not a page of this console: cross-site requests are refused";
  }
  return std::nullopt;
}

}  // namespace netmc::console
