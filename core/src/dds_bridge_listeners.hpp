#pragma once
// The DdsBridge's listeners that dds_bridge.cpp creates and other files implement, and what they count.
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>

#include "dds_bridge.hpp"

namespace wysiwyf::detail {

// Counts what DDS reports for one endpoint; read by health() from another thread.
struct DdsBridge::Counters {
  std::atomic<std::uint64_t> incompatible{0};
  std::atomic<int> last_policy{0};
  std::atomic<std::uint64_t> lost{0};
  std::atomic<std::uint64_t> ignored{0};          // samples of a writer that does not own a one-writer topic
  std::atomic<std::uint64_t> deadline_missed{0};  // reader: periods of its deadline without a sample
};

// A topic's DataReader's listener: pushes its samples into the local queues (dds_reader_link.cpp).
struct DdsBridge::ReaderLink final : public eprosima::fastdds::dds::DataReaderListener {
  ReaderLink(DdsBridge& b, TopicChannelBase& c);
  ~ReaderLink() override;
  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;
  // The deadline QoS (the pipeline's `qos: {port: {deadline: ..}}`): a writer whose process is
  // frozen, cut off or overloaded is named as soon as a period passes without its sample, once
  // per silence; the misses are counted (health()).
  void on_requested_deadline_missed(eprosima::fastdds::dds::DataReader*,
                                    const eprosima::fastdds::dds::RequestedDeadlineMissedStatus& status) override;
  // A one-writer topic written by this pipeline (expected_writer set) takes samples only from
  // that process group's participant: any other writer is refused, first or after the owner was
  // lost (a killed display is not replaced by whoever writes next). Among the writers it may
  // take, it follows the first it hears until that writer leaves, loses its liveliness, or, where
  // the topic has a deadline, misses it (a killed process's writer is unmatched only after its
  // participant's lease, 5 s, and its restarted successor would wait that long). DDS
  // ownership already passes only its owner's samples, but it would hand the topic to a newcomer
  // of equal strength and lower GUID. Another writer's samples are dropped, counted and it is
  // named once.
  bool follows(const eprosima::fastdds::dds::InstanceHandle_t& writer);
  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& status) override;
  // A one-writer topic's owner whose liveliness lapsed (dds::kOneWriterLiveliness: its process
  // killed or frozen) is let go: the next writer heard that may take the topic owns it.
  void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                             const eprosima::fastdds::dds::LivelinessChangedStatus& status) override;
  void on_requested_incompatible_qos(eprosima::fastdds::dds::DataReader*,
                                     const eprosima::fastdds::dds::RequestedIncompatibleQosStatus& status) override;
  void on_sample_lost(eprosima::fastdds::dds::DataReader*,
                      const eprosima::fastdds::dds::SampleLostStatus& status) override;
  DdsBridge& bridge;
  TopicChannelBase& channel;
  void* sample;
  const bool one_writer;
  std::string expected_writer;  // "<pipeline>/<group>" whose writers alone may own the topic; "" any
  std::mutex owner_mutex;       // the receive, discovery and event threads
  std::optional<eprosima::fastdds::dds::InstanceHandle_t> owner;
  std::set<eprosima::fastdds::dds::InstanceHandle_t> named;  // the writers said to be ignored
  std::atomic<bool> late{false};                             // a deadline passed without a sample, and none came since
  std::optional<eprosima::fastdds::dds::InstanceHandle_t> last_writer;  // whose sample came last (owner_mutex)
  const std::string* origin_ = nullptr;                                 // its process's name, interned (owner_mutex)
  Counters counters;
};

// Who is who on the domain: participants' names by their GUID prefix, for messages that name a writer.
// A process of the same pipeline ("<pipeline>/<group>...") that leaves or goes silent is said.
// Its calls, and the bridge's look-ups in it, are in dds_participant_names.cpp.
struct DdsBridge::ParticipantNames final : public eprosima::fastdds::dds::DomainParticipantListener {
  ParticipantNames(DdsBridge& b, std::string pipeline) : bridge(b), pipeline_prefix(std::move(pipeline) + "/") {}
  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;
  // Readers that declared a latency budget of dds::kBatchingPeriod or more (Fast DDS announces a
  // reader before it matches any writer of ours).
  void on_subscriber_discovery(eprosima::fastdds::dds::DomainParticipant*,
                               eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override;
  DdsBridge& bridge;
  const std::string pipeline_prefix;
  std::mutex mutex;
  std::map<eprosima::fastrtps::rtps::GuidPrefix_t, std::string> names;
  std::set<eprosima::fastrtps::rtps::GUID_t> batch_readers;
};

}  // namespace wysiwyf::detail
