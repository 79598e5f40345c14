#include "wysiwyf/dds_security.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace wysiwyf::dds {

namespace fs = std::filesystem;

std::vector<std::string> security_files(const SecurityIdentity& id) {
  const fs::path keys = id.keys_dir;
  const fs::path own = keys / id.identity;
  return {(keys / "identity_ca.pem").string(), (own / "cert.pem").string(),
          (own / "key.pem").string(),          (keys / "permissions_ca.pem").string(),
          (keys / "governance.p7s").string(),  (own / "permissions.p7s").string()};
}

void enable_security(eprosima::fastdds::dds::DomainParticipantQos& qos, const SecurityIdentity& id) {
  const std::vector<std::string> files = security_files(id);
  std::string missing;
  for (const auto& f : files)
    if (!fs::exists(f)) missing += (missing.empty() ? "" : ", ") + f;
  if (!missing.empty())
    throw std::invalid_argument("DDS-Security identity '" + id.identity + "' in '" + id.keys_dir + "': missing " +
                                missing + " (scripts/security makes them from a policy)");
  // Fast DDS reads the files by URI; absolute, so a process's working folder does not matter.
  const auto uri = [](const std::string& f) { return "file://" + fs::absolute(f).lexically_normal().string(); };
  auto& p = qos.properties().properties();
  // Participant announcements (SPDP) travel in clear even with security: do not add the host,
  // user and process id that Fast DDS announces by default (for its monitor tool).
  p.erase(std::remove_if(p.begin(), p.end(),
                         [](const auto& property) { return property.name().rfind("fastdds.physical_data.", 0) == 0; }),
          p.end());
  p.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  p.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_ca", uri(files[0]));
  p.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_certificate", uri(files[1]));
  p.emplace_back("dds.sec.auth.builtin.PKI-DH.private_key", uri(files[2]));
  p.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  p.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions_ca", uri(files[3]));
  p.emplace_back("dds.sec.access.builtin.Access-Permissions.governance", uri(files[4]));
  p.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions", uri(files[5]));
  p.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

}  // namespace wysiwyf::dds
