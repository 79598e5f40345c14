#include "dds_session.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include "wysiwyf/dds.hpp"
#include "wysiwyf/pipeline_spec.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;

// --domain / --pipeline / --transport -> a participant that listens to discovery.
void open(Args& args, Session& s) {
  int domain = 0;
  std::string transport = "default";
  if (auto file = args.value("--pipeline")) {
    try {
      const PipelineSpec spec = load_pipeline(*file);
      domain = spec.domain_id();
      transport = spec.transport();
    } catch (const ConfigError& e) {
      throw UsageError(std::string("cannot read --pipeline: ") + e.what());
    }
  }
  if (auto d = args.value("--domain")) {
    try {
      domain = std::stoi(*d);
    } catch (...) {
      throw UsageError("--domain: found '" + *d + "'; expected a domain id from 0 to 232");
    }
  }
  if (auto t = args.value("--transport")) transport = *t;
  DomainParticipantQos qos;
  try {
    qos = dds::participant_qos(transport, "wysiwyf-cli");
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  s.domain = domain;
  s.transport = transport;
  // Discovery only: with the default mask the listener would also take DATA_ON_READERS, which
  // DDS then calls instead of the readers' own on_data_available.
  s.participant =
      DomainParticipantFactory::get_instance()->create_participant(domain, qos, &s.discovery, StatusMask::none());
  if (!s.participant) throw std::runtime_error("cannot join DDS domain " + std::to_string(domain));
}

}  // namespace wysiwyf::cli
