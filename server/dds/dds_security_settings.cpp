#include "server/dds/dds_security_settings.hpp"

#include <filesystem>
#include <stdexcept>

namespace netmc::dds {

// The standard participant properties of the built-in plugins.
void add_security_properties(eprosima::fastdds::dds::DomainParticipantQos& qos, const std::string& directory, const std::string& identity) {
  const std::filesystem::path dir = std::filesystem::absolute(directory);
  const auto file = [&](const std::string& name) {
    const auto path = dir / name;
    if (!std::filesystem::is_regular_file(path)) {
      throw std::invalid_argument("--security: " + path.string() + " not found (scripts/make-lab-pki.sh makes it)");
    }
    return "file://" + path.string();
  };
  auto& properties = qos.properties().properties();
  properties.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_ca", file("ca.pem"));
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_certificate", file(identity + ".pem"));
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.private_key", file(identity + ".key"));
  properties.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions_ca", file("ca.pem"));
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.governance", file("governance.p7s"));
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions", file("permissions.p7s"));
  properties.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

}  // namespace netmc::dds
