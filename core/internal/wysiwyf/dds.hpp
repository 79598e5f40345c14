#pragma once
// How the kernel sets up Fast DDS, shared with the command line tools and the benchmarks so they
// meet a pipeline on the same transports and QoS.
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "wysiwyf/qos.hpp"

namespace wysiwyf::dds {

// The transports a pipeline's `dds.transport` names.
const std::vector<std::string>& transport_names();

// "default": Fast DDS's built-in UDPv4 and shared memory, discoverable from other machines.
// "local": shared memory and UDPv4 on 127.0.0.1 only (tests: nothing leaves the machine).
// "shm": shared memory only. "udp": UDPv4 only. "loopback": UDPv4 on 127.0.0.1 only (one host's
// processes over the network path: what a capture on `lo` sees).
// Throws std::invalid_argument for any other name. Every participant's lease is kLeaseSeconds,
// announced twice a second.
eprosima::fastdds::dds::DomainParticipantQos participant_qos(const std::string& transport, const std::string& name);
constexpr int kLeaseSeconds = 5;
// A one-writer topic's writer asserts its liveliness (DDS MANUAL_BY_TOPIC: its samples, and the
// bridge's publisher thread kOneWriterAssertions times per lease) and its readers ask for this
// lease: a writer whose process was killed or frozen is known lost after it, not after the
// participant's kLeaseSeconds, so that a restarted process of the same group can take over a
// topic without a deadline (the arm's requests).
constexpr std::chrono::milliseconds kOneWriterLiveliness{500};
constexpr int kOneWriterAssertions = 5;
// Whether participant_qos gives that transport shared memory (all but "udp" and "loopback").
bool uses_shared_memory(const std::string& transport);
// Whether endpoints may use Fast DDS data sharing between processes of one host: where the
// transport has shared memory. "udp" and "loopback" keep samples on the network path, even
// between processes of one host (or of network namespaces that share its /dev/shm).
bool uses_data_sharing(const std::string& transport);

// `instances`: how many instances (key values) a keyed topic may have, each with its own history
// of qos.depth samples. (Fast DDS's default is 10: the diagnostics of an 11th component were
// silently refused.)
eprosima::fastdds::dds::DataWriterQos writer_qos(const Qos& qos, int instances = 1);
eprosima::fastdds::dds::DataReaderQos reader_qos(const Qos& qos, int instances = 1);

// The ports of one process on a topic that its one DDS endpoint there stands for: a writer where
// the process has writers (its readers then served in-process, unseen by DDS), else a reader for
// its readers. Announced in the endpoint's user data, so that tools count every port of every
// process (topic list, the bridge's connection graph), the in-process ones too.
struct EndpointPorts {
  int writers = 0;
  int readers = 0;
};
std::vector<unsigned char> endpoint_ports_user_data(const EndpointPorts& ports);
// What another endpoint's user data announces; nullopt where it is not this form (a tool, another
// DDS program) or out of range (hostile: counts above kMaxAnnouncedPorts are not believed).
std::optional<EndpointPorts> endpoint_ports_from_user_data(const std::vector<unsigned char>& data);
constexpr int kMaxAnnouncedPorts = 100000;

// The instances a keyed topic of a pipeline may have: one per component (the diagnostics), with room.
constexpr int kKeyedTopicInstances = 256;

// A reader that declares a DDS latency budget of at least kBatchingPeriod lets a pipeline on the
// real clock send it samples in batches, every kBatchingPeriod, instead of waking its publisher
// thread after every tick (that wake is a cross-CPU interrupt that slows a 1 kHz loop's next
// tick: docs/design/monitoring-batches.md). A reader without one (another process of the
// pipeline) gets each sample as it is written. The monitoring tools declare kMonitorLatencyBudget.
constexpr std::chrono::milliseconds kBatchingPeriod{5};
constexpr std::chrono::milliseconds kMonitorLatencyBudget{50};
// Sets a reader's latency budget so that DDS announces it (Fast DDS sends a policy left unchanged
// as its default, zero, without saying so).
void set_latency_budget(eprosima::fastdds::dds::DataReaderQos& qos, std::chrono::nanoseconds budget);

// A Fast DDS QosPolicyId_t by its DDS name ("RELIABILITY", "DURABILITY", ...).
std::string qos_policy_name(int policy_id);
// Why a remote endpoint was refused, from this side's port QoS: e.g. "RELIABILITY: a reader
// wants reliable, this writer offers best effort". `writer`: this side writes.
std::string incompatibility(int policy_id, const Qos& ours, bool writer);

}  // namespace wysiwyf::dds
