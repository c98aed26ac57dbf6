#pragma once
// What a netmc process asks of its DDS participant (domain, transport, interfaces, discovery,
// profiles, security); see docs/architecture.md.

#include <string>
#include <vector>

namespace netmc::dds {

enum class Transport {
  builtin,   // shared memory between processes of one host, plus UDPv4 on the chosen interfaces
  udp,       // UDPv4 only: what real hosts use and what network emulation sees
};

struct DdsOptions {
  int domain_id = 0;
  Transport transport = Transport::builtin;
  // IPv4 addresses or interface names; empty: loopback only. "any": every interface.
  std::vector<std::string> interfaces;
  // Fast DDS Discovery Servers HOST:PORT; the i-th is the server started with id i
  // (`fastdds discovery -i i -l HOST -p PORT`). Empty: multicast discovery (or unicast on
  // loopback).
  std::vector<std::string> discovery_servers;
  std::string xml_profile_file;     // optional Fast DDS XML profiles, loaded first
  std::string participant_profile;  // optional participant profile name in that file
  // DDS Security (scripts/make-lab-pki.sh): the directory with ca.pem, governance.p7s,
  // permissions.p7s and this participant's NAME.pem and NAME.key, NAME being `name`. Empty: off.
  std::string security_dir;
  std::string name = "netmc";
};

}  // namespace netmc::dds
