#pragma once
// The DDS flags shared by netmc-server and netmc-axis.

#include <CLI/CLI.hpp>

#include "server/dds/dds_context.hpp"

namespace netmc::dds {

inline void add_dds_options(CLI::App& app, DdsOptions& options) {
  app.add_option("--domain", options.domain_id, "DDS domain id")->check(CLI::Range(0, 232));
  app.add_option_function<std::string>(
         "--transport",
         [&options](const std::string& value) {
           options.transport = value == "udp" ? Transport::udp : Transport::builtin;
         },
         "DDS transport: builtin (shared memory on one host, UDP between hosts) or udp (UDPv4 "
         "only, needed for honest delay studies and separate hosts)")
      ->check(CLI::IsMember({"builtin", "udp"}));
  app.add_option("--dds-profile", options.xml_profile_file,
                 "Fast DDS XML profiles file (QoS, transports)");
  app.add_option("--dds-participant-profile", options.participant_profile,
                 "Participant profile name in that file");
}

}  // namespace netmc::dds
