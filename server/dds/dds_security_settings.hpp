#pragma once
// The DDS Security properties of a participant (Fast DDS's built-in plugins, files made by
// scripts/make-lab-pki.sh); see docs/architecture.md.

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include <string>

namespace netmc::dds {

// PKI-DH authentication, access control with signed governance and permissions, AES-GCM, with
// the lab's files in `directory` and this participant's NAME.pem/NAME.key, NAME = `identity`.
// Throws std::invalid_argument naming --security for a missing file.
void add_security_properties(eprosima::fastdds::dds::DomainParticipantQos& qos, const std::string& directory,
                             const std::string& identity);

}  // namespace netmc::dds
