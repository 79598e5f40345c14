#pragma once
// DDS-Security for one participant: the identity it authenticates with (PKI-DH), the signed
// governance and permissions documents it is checked against (Access-Permissions), and AES-GCM
// for what the governance protects (every message, or some topics' submessages). The files are what scripts/security makes:
//   <keys>/identity_ca.pem, <keys>/permissions_ca.pem, <keys>/governance.p7s,
//   <keys>/<identity>/cert.pem, key.pem, permissions.p7s
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include <string>
#include <vector>

namespace wysiwyf::dds {

struct SecurityIdentity {
  std::string keys_dir;  // scripts/security's output folder
  std::string identity;  // a folder in it, one per process group or monitor
};

// The files `id` needs, in the order the plugins read them.
std::vector<std::string> security_files(const SecurityIdentity& id);

// Sets the security plugins' properties on `qos`, and removes the host, user and process id that
// Fast DDS would announce in clear. Throws std::invalid_argument naming every file
// of security_files(id) that is missing (nothing is set then).
void enable_security(eprosima::fastdds::dds::DomainParticipantQos& qos, const SecurityIdentity& id);

}  // namespace wysiwyf::dds
