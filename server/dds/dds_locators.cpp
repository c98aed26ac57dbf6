#include "server/dds/dds_locators.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

namespace netmc::dds {
namespace {

using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

bool is_ipv4(const std::string& text) {
  in_addr address{};
  return ::inet_pton(AF_INET, text.c_str(), &address) == 1;
}

std::vector<std::string> interface_addresses(const std::string& name) {
  std::vector<std::string> out;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return out;
  for (ifaddrs* it = list; it; it = it->ifa_next) {
    if (!it->ifa_addr || it->ifa_addr->sa_family != AF_INET || name != it->ifa_name) continue;
    char text[INET_ADDRSTRLEN] = {};
    const auto* in = reinterpret_cast<const sockaddr_in*>(it->ifa_addr);
    if (::inet_ntop(AF_INET, &in->sin_addr, text, sizeof text)) out.emplace_back(text);
  }
  ::freeifaddrs(list);
  return out;
}

Locator_t udp_locator(const std::string& address, std::uint32_t port) {
  Locator_t locator;
  locator.kind = LOCATOR_KIND_UDPv4;
  IPLocator::setIPv4(locator, address);
  locator.port = port;
  return locator;
}

eprosima::fastdds::rtps::RemoteServerAttributes discovery_server(const std::string& text, int id) {
  const auto colon = text.rfind(':');
  std::string host = colon == std::string::npos ? "" : text.substr(0, colon);
  if (host == "localhost") host = "127.0.0.1";
  int port = -1;
  if (colon != std::string::npos && colon + 1 < text.size() && text.size() - colon <= 6 &&
      std::all_of(text.begin() + static_cast<std::ptrdiff_t>(colon) + 1, text.end(),
                  [](char c) { return c >= '0' && c <= '9'; })) {
    port = std::stoi(text.substr(colon + 1));
  }
  if (!is_ipv4(host) || port < 1 || port > 65535) {
    throw std::invalid_argument("--discovery-server: expected IPV4:PORT[,IPV4:PORT...], got '" + text + "'");
  }
  eprosima::fastdds::rtps::RemoteServerAttributes server;
  eprosima::fastdds::rtps::get_server_client_default_guidPrefix(id, server.guidPrefix);
  server.metatrafficUnicastLocatorList.push_back(udp_locator(host, static_cast<std::uint32_t>(port)));
  return server;
}

}  // namespace

std::vector<std::string> resolve_interfaces(const std::vector<std::string>& interfaces) {
  if (interfaces.empty()) return {"127.0.0.1"};
  std::vector<std::string> out;
  for (const auto& entry : interfaces) {
    if (entry == "any") {
      if (interfaces.size() != 1) throw std::invalid_argument("--interface: 'any' stands alone");
      return {"any"};
    }
    if (entry.size() > 64) throw std::invalid_argument("--interface: entry longer than 64 characters");
    if (is_ipv4(entry)) {
      out.push_back(entry);
      continue;
    }
    const auto addresses = interface_addresses(entry);
    if (addresses.empty()) {
      throw std::invalid_argument("--interface: '" + entry +
                                  "' is neither an IPv4 address nor an interface with one on this "
                                  "host (expected e.g. 127.0.0.1, lo or eth0)");
    }
    out.insert(out.end(), addresses.begin(), addresses.end());
  }
  return out;
}

std::string configure_transport(eprosima::fastdds::dds::DomainParticipantQos& qos, const DdsOptions& options) {
  auto& builtin = qos.wire_protocol().builtin;
  std::vector<std::string> addresses = resolve_interfaces(options.interfaces);
  const bool any = addresses.size() == 1 && addresses[0] == "any";
  const auto on_loopback = [](const std::string& a) { return a.rfind("127.", 0) == 0 || a.rfind("localhost:", 0) == 0; };
  const bool loopback_only = !any && std::all_of(addresses.begin(), addresses.end(), on_loopback);
  std::string loopback_added;
  if (!any && !std::any_of(addresses.begin(), addresses.end(), on_loopback)) {
    // Fast DDS talks to a Discovery Server on this host (on loopback, or on one of its own
    // addresses: both ends then use loopback) over loopback, which a whitelist without it
    // forbids: the process would never find anyone and never know why. Loopback opens nothing
    // beyond this host and the user plainly meant that server, so it is added (and said) rather
    // than refusing the start.
    const auto on_this_host = [&](const std::string& server) {
      const std::string host = server.substr(0, server.rfind(':'));
      return on_loopback(server) || std::find(addresses.begin(), addresses.end(), host) != addresses.end();
    };
    for (const auto& server : options.discovery_servers) {
      if (!on_this_host(server)) continue;
      addresses.push_back("127.0.0.1");
      loopback_added = ", 127.0.0.1 added for the discovery server " + server;
      std::string given;
      for (const auto& entry : options.interfaces) given += (given.empty() ? "" : ",") + entry;
      spdlog::warn("--interface {} does not include loopback, over which Fast DDS reaches the discovery server {} "
                   "on this host: 127.0.0.1 added to the interfaces DDS may use",
                   given, server);
      break;
    }
  }
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  if (!any) udp->interfaceWhiteList = addresses;
  udp->maxInitialPeersRange = kMaxLoopbackParticipants;
  qos.transport().use_builtin_transports = false;
  if (options.transport == Transport::builtin) {
    qos.transport().user_transports.push_back(
        std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>());
  }
  qos.transport().user_transports.push_back(udp);

  std::string where;
  for (const auto& a : addresses) where += (where.empty() ? "" : ",") + a;
  if (!options.discovery_servers.empty()) {
    builtin.discovery_config.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::CLIENT;
    int id = 0;
    std::string servers;
    for (const auto& text : options.discovery_servers) {
      builtin.discovery_config.m_DiscoveryServers.push_back(discovery_server(text, id++));
      servers += (servers.empty() ? "" : ",") + text;
    }
    // The client's own discovery traffic stays on the chosen interface, not a multicast group.
    builtin.metatrafficMulticastLocatorList.clear();
    if (!any) {
      builtin.metatrafficUnicastLocatorList.clear();
      builtin.metatrafficUnicastLocatorList.push_back(udp_locator(addresses[0], 0));
    }
    where += ", discovery server " + servers + loopback_added;
  } else if (loopback_only) {
    // Loopback has no multicast: find the other participants of this host by unicast on
    // the well-known ports of the first kMaxLoopbackParticipants participant ids, and bind
    // nothing to a wildcard or multicast address.
    builtin.metatrafficMulticastLocatorList.clear();
    builtin.metatrafficUnicastLocatorList.clear();
    builtin.metatrafficUnicastLocatorList.push_back(udp_locator(addresses[0], 0));
    qos.wire_protocol().default_unicast_locator_list.clear();
    qos.wire_protocol().default_unicast_locator_list.push_back(udp_locator(addresses[0], 0));
    builtin.initialPeersList.clear();
    builtin.initialPeersList.push_back(udp_locator(addresses[0], 0));
    where += ", unicast discovery";
  } else {
    where += ", multicast discovery";
  }
  return std::string(options.transport == Transport::udp ? "UDPv4" : "shared memory + UDPv4") + " on " +
         (any ? std::string("every interface") : where);
}

}  // namespace netmc::dds
