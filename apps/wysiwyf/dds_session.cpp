#include "dds_session.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include <fastdds/dds/topic/TypeSupport.hpp>

#include <iostream>

#include "raw_cdr_type.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/dds_discovery.hpp"
#include "wysiwyf/dds_log.hpp"
#include "wysiwyf/dds_security.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/stale_shared_memory.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;

DataReader* open_raw_reader(Session& s, Subscriber* subscriber, const std::string& topic, const TopicInfo& info,
                            int depth, DataReaderListener* listener, const StatusMask& mask) {
  // The type under the writer's name (registering it again for another topic is a no-op).
  TypeSupport support(new RawCdrType(info.type, info.keyed));
  support.register_type(s.participant, info.type);
  Topic* t = s.participant->find_topic(topic, eprosima::fastrtps::Duration_t(0, 0));
  if (!t) t = s.participant->create_topic(topic, info.type, TOPIC_QOS_DEFAULT);
  Qos qos = Qos::reliable(depth);
  qos.reliability = info.reliability == RELIABLE_RELIABILITY_QOS ? Reliability::kReliable : Reliability::kBestEffort;
  qos.durability = info.durability == VOLATILE_DURABILITY_QOS ? Durability::kVolatile : Durability::kTransientLocal;
  qos.single_writer = info.one_writer;
  DataReaderQos rq = dds::reader_qos(qos, info.keyed ? dds::kKeyedTopicInstances : 1);
  rq.endpoint().history_memory_policy = eprosima::fastrtps::rtps::DYNAMIC_REUSABLE_MEMORY_MODE;
  rq.data_sharing().off();  // samples of unknown size: no fixed-size shared buffers
  dds::set_latency_budget(rq, s.latency_budget);
  DataReader* reader = t ? subscriber->create_datareader(t, rq, listener, mask) : nullptr;
  if (!reader) std::cerr << "cannot read topic '" << topic << "' (" << info.type << ")\n";
  return reader;
}

// --domain / --pipeline / --transport -> a participant that listens to discovery.
void open(Args& args, Session& s) {
  dds::route_fast_dds_log();
  int domain = 0;
  std::string transport = "default";
  std::string keys;
  std::vector<std::string> servers;
  if (auto file = args.value("--pipeline")) {
    try {
      const PipelineSpec spec = load_pipeline(*file);
      domain = spec.domain_id();
      transport = spec.transport();
      keys = spec.security.keys.value;
      servers = spec.dds.discovery_servers.value;
    } catch (const ConfigError& e) {
      throw UsageError(std::string("cannot read --pipeline: ") + e.what());
    }
  }
  domain = static_cast<int>(whole_option(args, "--domain", domain, 0, 232, "a domain id from 0 to 232"));
  if (auto t = args.value("--transport")) transport = *t;
  if (args.flag("--prompt")) s.latency_budget = std::chrono::nanoseconds(0);
  DomainParticipantQos qos;
  try {
    qos = dds::participant_qos(transport, "wysiwyf-cli");
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (auto list = args.value("--discovery-server")) {
    servers.clear();
    std::stringstream items(*list);
    for (std::string item; std::getline(items, item, ',');) servers.push_back(item);
  }
  try {  // a tool is told about every participant and endpoint, not only those it matches
    if (!servers.empty()) dds::use_discovery_servers(qos, servers, /*see_everything=*/true);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--discovery-server: ") + e.what());
  }
  // On a secured domain a tool authenticates too: as the monitor identity unless told otherwise.
  if (auto k = args.value("--keys")) keys = *k;
  const std::optional<std::string> identity = args.value("--identity");
  if (identity && keys.empty())
    throw UsageError("--identity " + *identity +
                     ": expected --keys DIR (the folder scripts/security made) or a "
                     "--pipeline whose security.keys names it");
  if (!keys.empty()) {
    try {
      dds::enable_security(qos, {keys, identity.value_or("monitor")});
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    s.identity = identity.value_or("monitor");
  }
  s.domain = domain;
  s.transport = transport;
  dds::remove_stale_shared_memory_once(transport,
                                       [](const std::string& line) { std::cerr << "[dds] " << line << "\n"; });
  // Discovery only: with the default mask the listener would also take DATA_ON_READERS, which
  // DDS then calls instead of the readers' own on_data_available.
  s.participant =
      DomainParticipantFactory::get_instance()->create_participant(domain, qos, &s.discovery, StatusMask::none());
  if (!s.participant)
    throw std::runtime_error("cannot join DDS domain " + std::to_string(domain) +
                             (s.identity.empty() ? "" : " as DDS-Security identity '" + s.identity + "' of " + keys));
}

}  // namespace wysiwyf::cli
