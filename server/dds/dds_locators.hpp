#pragma once
// Where a participant talks: the interfaces of --interface resolved to addresses, its UDP and
// shared-memory transports, and its discovery (multicast, unicast on loopback, or Discovery
// Servers); see docs/architecture.md.

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include <string>
#include <vector>

#include "server/dds/dds_options.hpp"

namespace netmc::dds {

// Participants on one host that find each other by unicast on loopback.
inline constexpr int kMaxLoopbackParticipants = 64;

// The interfaces of `--interface`, resolved to IPv4 addresses (names through getifaddrs).
// Throws std::invalid_argument naming the flag for an unknown name or a malformed address.
std::vector<std::string> resolve_interfaces(const std::vector<std::string>& interfaces);

// Sets the participant's transports, locators and discovery from `options`; returns what it
// chose in words ("UDPv4 on 127.0.0.1, unicast discovery"). The participant talks on the chosen
// interfaces only (loopback unless told otherwise): a motion-control network is opened on
// purpose, not by default.
std::string configure_transport(eprosima::fastdds::dds::DomainParticipantQos& qos, const DdsOptions& options);

}  // namespace netmc::dds
