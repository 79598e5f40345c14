#pragma once
// Discovery without multicast: a Fast DDS Discovery Server (`wysiwyf discovery-server`) that the
// pipeline's participants and the tools find by address. Server N has Fast DDS's default GUID
// prefix for id N (as `fastdds discovery -i N` and ROS_DISCOVERY_SERVER use), so a list of
// addresses is all a participant needs.
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include <string>
#include <vector>

namespace wysiwyf::dds {

// "10.0.0.5:11811" -> true; anything else (a host name, no port) -> false.
bool is_server_address(const std::string& address);

// Makes `qos` a client of the servers at `addresses` (server i of the list has id i). A client
// learns only what its own endpoints need; `see_everything` (the monitoring tools) makes it a
// super client, told about every participant and endpoint. Throws std::invalid_argument for an
// address that is not IPv4:port.
void use_discovery_servers(eprosima::fastdds::dds::DomainParticipantQos& qos, const std::vector<std::string>& addresses,
                           bool see_everything);

// A discovery server with id `id` listening on `address` (IPv4:port), over UDP.
eprosima::fastdds::dds::DomainParticipantQos discovery_server_qos(const std::string& address, int id);

}  // namespace wysiwyf::dds
