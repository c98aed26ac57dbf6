#pragma once
// The DDS flags shared by netmc-server and netmc-axis.
// See docs/architecture.md, "Processes".

#include <CLI/CLI.hpp>

#include "server/dds/dds_context.hpp"
#include "server/dds/dds_locators.hpp"
#include "server/dds/time_base.hpp"

namespace netmc::dds {

inline std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::string item;
  for (char c : text + ",") {
    if (c == ',') {
      if (!item.empty()) out.push_back(item);
      item.clear();
    } else {
      item += c;
    }
  }
  return out;
}

inline void add_dds_options(CLI::App& app, DdsOptions& options) {
  // Domain ids keep every participant's well-known port below 65536 with 64 participant ids.
  app.add_option("--domain", options.domain_id, "DDS domain id (0-230)")
      ->check(CLI::Range(0, 230))
      ->envname("NETMC_DOMAIN");
  app.add_option_function<std::string>(
         "--transport",
         [&options](const std::string& value) {
           options.transport = value == "udp" ? Transport::udp : Transport::builtin;
         },
         "DDS transport: builtin (shared memory between processes of one host, plus UDP) or udp "
         "(UDPv4 only, needed for honest delay studies and separate hosts)")
      ->check(CLI::IsMember({"builtin", "udp"}))
      ->envname("NETMC_TRANSPORT");
  app.add_option_function<std::string>(
         "--interface",
         [&options](const std::string& value) {
           options.interfaces = split_list(value);
           resolve_interfaces(options.interfaces);  // fail at parse time, naming the flag
         },
         "Network interfaces DDS may use: IPv4 addresses or names, comma-separated (default: "
         "loopback only, 127.0.0.1; 'any' for every interface)")
      ->type_name("ADDR|NAME[,...]")
      ->envname("NETMC_INTERFACE");
  app.add_option_function<std::string>(
         "--discovery-server",
         [&options](const std::string& value) { options.discovery_servers = split_list(value); },
         "Fast DDS Discovery Servers instead of multicast discovery; the i-th runs "
         "`fast-discovery-server -i i -l IPV4 -p PORT` (Debian's fastdds-tools); a warning if none "
         "answers within 5 s")
      ->type_name("IPV4:PORT[,...]")
      ->envname("NETMC_DISCOVERY_SERVER");
  app.add_option("--dds-profile", options.xml_profile_file,
                 "Fast DDS XML profiles file (QoS, transports); FASTRTPS_DEFAULT_PROFILES_FILE is "
                 "honoured too");
  app.add_option("--dds-participant-profile", options.participant_profile,
                 "Participant profile name in that file (replaces --interface and --transport)");
  app.add_option("--security", options.security_dir,
                 "DDS Security: directory made by scripts/make-lab-pki.sh (authenticated, access-controlled, "
                 "encrypted); this participant's certificate is NAME.pem, NAME its node or --dds-name")
      ->envname("NETMC_SECURITY");
}

inline void add_time_base_option(CLI::App& app, TimeBase& base) {
  app.add_option_function<std::string>(
         "--time-base", [&base](const std::string& value) { base = parse_time_base(value); },
         "Clock that schedules realtime jobs: monotonic (default; each host's own, offsets "
         "measured), realtime or tai (where chrony or linuxptp keeps hosts in step; the residual "
         "offset is still measured)")
      ->check(CLI::IsMember({"monotonic", "realtime", "tai"}));
}

}  // namespace netmc::dds
