// wysiwyf discovery-server: a Fast DDS Discovery Server, for networks without multicast. The
// pipelines name it (dds: {discovery_server: A:P}), the tools take --discovery-server A:P.
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include <chrono>
#include <iostream>
#include <thread>

#include "cli.hpp"
#include "wysiwyf/dds_discovery.hpp"
#include "wysiwyf/runtime.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;

int cmd_discovery_server(Args args) {
  const std::string address = args.value("--listen").value_or("0.0.0.0:11811");
  const int id = static_cast<int>(whole_option(args, "--id", 0, 0, 255, "a server id from 0 to 255"));
  const int domain = static_cast<int>(whole_option(args, "--domain", 0, 0, 232, "a domain id from 0 to 232"));
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  DomainParticipantQos qos;
  try {
    qos = dds::discovery_server_qos(address, id);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  install_stop_signal_handlers();
  DomainParticipant* server = DomainParticipantFactory::get_instance()->create_participant(domain, qos);
  if (!server) {
    std::cerr << "cannot start a discovery server on " << address << " (is the address this host's, the port free?)\n";
    return 1;
  }
  std::cout << "discovery server " << id << " listening on " << address << " (Ctrl-C to stop)" << std::endl;
  while (!stop_signal_received()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  DomainParticipantFactory::get_instance()->delete_participant(server);
  return 0;
}

}  // namespace wysiwyf::cli
