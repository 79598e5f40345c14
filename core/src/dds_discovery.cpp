#include "wysiwyf/dds_discovery.hpp"

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastrtps/utils/IPLocator.h>

#include <regex>
#include <stdexcept>

#include "wysiwyf/dds.hpp"

namespace wysiwyf::dds {

using eprosima::fastdds::dds::DomainParticipantQos;
using eprosima::fastrtps::rtps::DiscoveryProtocol_t;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

namespace {

Locator_t locator_of(const std::string& address) {
  static const std::regex form(R"(^(\d{1,3}(?:\.\d{1,3}){3}):(\d{1,5})$)");
  std::smatch m;
  if (!std::regex_match(address, m, form) || std::stoi(m[2]) > 65535)
    throw std::invalid_argument("discovery server '" + address +
                                "': expected an IPv4 address and port, like 10.0.0.5:11811");
  Locator_t locator;
  locator.kind = LOCATOR_KIND_UDPv4;
  if (!IPLocator::setIPv4(locator, m[1].str()))
    throw std::invalid_argument("discovery server '" + address + "': '" + m[1].str() + "' is not an IPv4 address");
  locator.port = static_cast<std::uint32_t>(std::stoi(m[2]));
  return locator;
}

eprosima::fastrtps::rtps::GuidPrefix_t prefix_of(int id) {
  eprosima::fastrtps::rtps::GuidPrefix_t prefix;
  if (!eprosima::fastdds::rtps::get_server_client_default_guidPrefix(id, prefix))
    throw std::invalid_argument("discovery server id " + std::to_string(id) + ": expected 0 to 255");
  return prefix;
}

}  // namespace

bool is_server_address(const std::string& address) {
  try {
    locator_of(address);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

void use_discovery_servers(DomainParticipantQos& qos, const std::vector<std::string>& addresses, bool see_everything) {
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.discoveryProtocol = see_everything ? DiscoveryProtocol_t::SUPER_CLIENT : DiscoveryProtocol_t::CLIENT;
  for (std::size_t i = 0; i < addresses.size(); ++i) {
    eprosima::fastdds::rtps::RemoteServerAttributes server;
    server.guidPrefix = prefix_of(static_cast<int>(i));
    server.metatrafficUnicastLocatorList.push_back(locator_of(addresses[i]));
    discovery.m_DiscoveryServers.push_back(server);
  }
}

DomainParticipantQos discovery_server_qos(const std::string& address, int id) {
  DomainParticipantQos qos = participant_qos("udp", "wysiwyf-discovery-server-" + std::to_string(id));
  qos.wire_protocol().builtin.discovery_config.discoveryProtocol = DiscoveryProtocol_t::SERVER;
  qos.wire_protocol().prefix = prefix_of(id);
  qos.wire_protocol().builtin.metatrafficUnicastLocatorList.push_back(locator_of(address));
  return qos;
}

}  // namespace wysiwyf::dds
