#pragma once
// What the monitoring commands (topic, record, play) share: a DDS participant on the domain of
// --domain / --pipeline / --transport that collects what remote writers and readers announce.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>

#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "cli.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/runtime.hpp"

namespace wysiwyf::cli {

using Clock = std::chrono::steady_clock;

struct TopicInfo {
  std::string type;
  std::set<std::string> writers, readers;  // GUIDs of the DDS endpoints
  // The ports each endpoint stands for (dds::EndpointPorts: a pipeline's process announces its
  // in-process readers on its writer); an endpoint that announces nothing is one port of its kind.
  std::map<std::string, dds::EndpointPorts> ports;
  int writer_ports() const { return count(writers, &dds::EndpointPorts::writers); }
  int reader_ports() const {
    int n = count(readers, &dds::EndpointPorts::readers);
    for (const auto& w : writers)
      if (const auto it = ports.find(w); it != ports.end()) n += it->second.readers;
    return n;
  }
  eprosima::fastdds::dds::ReliabilityQosPolicyKind reliability = eprosima::fastdds::dds::BEST_EFFORT_RELIABILITY_QOS;
  eprosima::fastdds::dds::DurabilityQosPolicyKind durability = eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS;
  bool keyed = false;       // the type has @key members (instances)
  bool one_writer = false;  // exclusive ownership (a robot's setpoint): a reader must ask for it too

 private:
  int count(const std::set<std::string>& endpoints, int dds::EndpointPorts::*kind) const {
    int n = 0;
    for (const auto& e : endpoints) {
      const auto it = ports.find(e);
      n += it == ports.end() ? 1 : it->second.*kind;
    }
    return n;
  }
};

// Collects the topics that remote writers and readers announce.
class Discovery : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant*,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override {
    using S = eprosima::fastrtps::rtps::WriterDiscoveryInfo::DISCOVERY_STATUS;
    std::ostringstream guid;
    guid << info.info.guid();
    std::lock_guard<std::mutex> lock(mutex_);
    auto& t = topics_[info.info.topicName().to_string()];
    t.type = info.info.typeName().to_string();
    if (info.status == S::REMOVED_WRITER) {
      t.writers.erase(guid.str());
      t.ports.erase(guid.str());
    } else {
      t.writers.insert(guid.str());
      if (const auto ports = dds::endpoint_ports_from_user_data(info.info.m_qos.m_userData.data_vec()))
        t.ports[guid.str()] = *ports;
      t.reliability = info.info.m_qos.m_reliability.kind;
      t.durability = info.info.m_qos.m_durability.kind;
      t.keyed = info.info.topicKind() == eprosima::fastrtps::rtps::WITH_KEY;
      t.one_writer = info.info.m_qos.m_ownership.kind == eprosima::fastdds::dds::EXCLUSIVE_OWNERSHIP_QOS;
    }
    cv_.notify_all();
  }
  void on_subscriber_discovery(eprosima::fastdds::dds::DomainParticipant*,
                               eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override {
    using S = eprosima::fastrtps::rtps::ReaderDiscoveryInfo::DISCOVERY_STATUS;
    std::ostringstream guid;
    guid << info.info.guid();
    std::lock_guard<std::mutex> lock(mutex_);
    auto& t = topics_[info.info.topicName().to_string()];
    t.type = info.info.typeName().to_string();
    if (info.status == S::REMOVED_READER) {
      t.readers.erase(guid.str());
      t.ports.erase(guid.str());
    } else {
      t.readers.insert(guid.str());
      if (const auto ports = dds::endpoint_ports_from_user_data(info.info.m_qos.m_userData.data_vec()))
        t.ports[guid.str()] = *ports;
    }
    cv_.notify_all();
  }

  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override {
    using S = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo::DISCOVERY_STATUS;
    std::ostringstream prefix;
    prefix << info.info.m_guid.guidPrefix;
    std::lock_guard<std::mutex> lock(mutex_);
    if (info.status == S::REMOVED_PARTICIPANT || info.status == S::DROPPED_PARTICIPANT)
      participants_.erase(prefix.str());
    else
      participants_[prefix.str()] = info.info.m_participantName.to_string();
  }

  std::map<std::string, TopicInfo> topics() {
    std::lock_guard<std::mutex> lock(mutex_);
    return topics_;
  }
  // Names a participant that discovery does not report (this process's own).
  void name_participant(const eprosima::fastdds::dds::DomainParticipant& p) {
    std::ostringstream prefix;
    prefix << p.guid().guidPrefix;
    std::lock_guard<std::mutex> lock(mutex_);
    participants_[prefix.str()] = p.get_qos().name().to_string();
  }
  // The name a participant announced, by an endpoint's GUID ("prefix|entity"); the GUID itself
  // where the participant is not known (yet).
  std::string participant_of(const std::string& endpoint_guid) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = participants_.find(endpoint_guid.substr(0, endpoint_guid.find('|')));
    return it == participants_.end() || it->second.empty() ? endpoint_guid : it->second;
  }
  // Waits until some writer announces `topic`; its info, or nullopt at the deadline.
  std::optional<TopicInfo> wait_for_writer(const std::string& topic, Clock::time_point deadline) {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_signal_received()) {
      auto it = topics_.find(topic);
      if (it != topics_.end() && !it->second.writers.empty()) return it->second;
      if (cv_.wait_until(lock, std::min(deadline, Clock::now() + std::chrono::milliseconds(100))) ==
              std::cv_status::timeout &&
          Clock::now() >= deadline)
        break;
    }
    return std::nullopt;
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  std::map<std::string, TopicInfo> topics_;
  std::map<std::string, std::string> participants_;  // GUID prefix -> announced name
};

struct Session {
  int domain = 0;
  std::string transport = "default";
  std::string identity;  // DDS-Security identity, "" on a plain domain
  // The latency budget its readers declare: dds::kMonitorLatencyBudget (a pipeline on the real
  // clock sends to them in batches, and watching does not slow its loops), zero with --prompt
  // (each sample as it is written).
  std::chrono::nanoseconds latency_budget = dds::kMonitorLatencyBudget;
  eprosima::fastdds::dds::DomainParticipant* participant = nullptr;
  Discovery discovery;
  ~Session() {
    if (participant) {
      participant->delete_contained_entities();
      eprosima::fastdds::dds::DomainParticipantFactory::get_instance()->delete_participant(participant);
    }
  }
};

// A reader of `topic` as raw CDR (raw_cdr_type.hpp) with the QoS of the writer found there, so
// that it matches, keeping up to `depth` samples: the recorder, the bridge and the monitor read
// every topic this way. nullptr (and a message on stderr) if DDS refuses.
eprosima::fastdds::dds::DataReader* open_raw_reader(Session& s, eprosima::fastdds::dds::Subscriber* subscriber,
                                                    const std::string& topic, const TopicInfo& info, int depth,
                                                    eprosima::fastdds::dds::DataReaderListener* listener,
                                                    const eprosima::fastdds::dds::StatusMask& mask);

// --domain / --pipeline / --transport -> a participant that listens to discovery (its domain
// and transport are kept in the session, for messages that say where a tool looked).
void open(Args& args, Session& s);

}  // namespace wysiwyf::cli
