#include <algorithm>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>

#include <memory>
#include <stdexcept>

#include "wysiwyf/dds.hpp"

namespace wysiwyf::dds {

using namespace eprosima::fastdds::dds;
using eprosima::fastdds::rtps::SharedMemTransportDescriptor;
using eprosima::fastdds::rtps::UDPv4TransportDescriptor;

const std::vector<std::string>& transport_names() {
  static const std::vector<std::string> names{"default", "local", "shm", "udp", "loopback"};
  return names;
}

bool uses_shared_memory(const std::string& transport) { return transport != "udp" && transport != "loopback"; }

bool uses_data_sharing(const std::string& transport) { return uses_shared_memory(transport); }

DomainParticipantQos participant_qos(const std::string& transport, const std::string& name) {
  DomainParticipantQos qos = PARTICIPANT_QOS_DEFAULT;
  qos.name(name);
  // A process that dies without a word (SIGKILL, power, a cut link) is dropped after this lease
  // (Fast DDS's default is 20 s, announced every 3): its writers are unmatched then, which frees
  // a one-writer topic for its restarted successor.
  qos.wire_protocol().builtin.discovery_config.leaseDuration = eprosima::fastrtps::Duration_t(kLeaseSeconds, 0);
  qos.wire_protocol().builtin.discovery_config.leaseDuration_announcementperiod =
      eprosima::fastrtps::Duration_t(0, 500'000'000);
  if (std::find(transport_names().begin(), transport_names().end(), transport) == transport_names().end())
    throw std::invalid_argument("unknown DDS transport '" + transport +
                                "'; expected default, local, shm, udp or loopback");
  // Fast DDS's built-in transports would do for "default", but with a 512 KB shared-memory
  // segment a 640x480 frame does not fit, goes over UDP, and a frame burst overflows the socket
  // buffers: a recorder loses samples of every topic of the demo. Configured here instead.
  qos.transport().use_builtin_transports = false;
  if (uses_shared_memory(transport)) {
    auto shm = std::make_shared<SharedMemTransportDescriptor>();
    // Room for a demo frame's burst of images (a dozen 640x480 RGB frames, 11 MB) twice over, so
    // the 1 kHz samples between them still find space while a slow reader (a recorder) copies them.
    shm->segment_size(32 * 1024 * 1024);
    // Each 64 KB fragment of an image is one message in a reader's port: a frame's burst is
    // ~200 of them, beyond Fast DDS's default queue of 512 once a starved reader misses a turn.
    shm->port_queue_capacity(4096);
    qos.transport().user_transports.push_back(shm);
  }
  if (transport != "shm") {
    auto udp = std::make_shared<UDPv4TransportDescriptor>();
    if (transport == "local" || transport == "loopback") udp->interfaceWhiteList.emplace_back("127.0.0.1");
    // Socket buffers for a burst of image fragments (the kernel caps them at net.core.rmem_max
    // and wmem_max).
    udp->receiveBufferSize = 4 * 1024 * 1024;
    udp->sendBufferSize = 4 * 1024 * 1024;
    qos.transport().user_transports.push_back(udp);
  }
  return qos;
}

static eprosima::fastrtps::Duration_t to_duration(std::int64_t ns) {
  return eprosima::fastrtps::Duration_t(static_cast<std::int32_t>(ns / 1'000'000'000),
                                        static_cast<std::uint32_t>(ns % 1'000'000'000));
}

namespace {

// What a writer and a reader of one port share: the port's QoS, and memory and transport choices.
template <class EndpointQos>
EndpointQos endpoint_qos(EndpointQos qos, const Qos& q, int instances) {
  qos.reliability().kind =
      q.reliability == Reliability::kReliable ? RELIABLE_RELIABILITY_QOS : BEST_EFFORT_RELIABILITY_QOS;
  qos.durability().kind =
      q.durability == Durability::kVolatile ? VOLATILE_DURABILITY_QOS : TRANSIENT_LOCAL_DURABILITY_QOS;
  qos.history().kind = KEEP_LAST_HISTORY_QOS;
  qos.history().depth = q.depth;
  if (q.deadline_ns > 0) qos.deadline().period = to_duration(q.deadline_ns);
  // One writer: a reader follows only the owner among the matched writers, and a writer with
  // shared ownership does not match at all (reported as an OWNERSHIP incompatibility).
  if (q.single_writer) {
    qos.ownership().kind = EXCLUSIVE_OWNERSHIP_QOS;
    // Asserted by each sample and by the bridge's publisher thread (DdsBridge::assert_liveliness).
    // (Not AUTOMATIC: Fast DDS 2.9 renews every automatic writer of a reader's domain on a
    // liveliness message from any participant, so a killed process's would stay alive.)
    qos.liveliness().kind = MANUAL_BY_TOPIC_LIVELINESS_QOS;
    qos.liveliness().lease_duration = to_duration(std::chrono::nanoseconds(kOneWriterLiveliness).count());
  }
  if (instances > 1) {
    qos.resource_limits().max_instances = instances;
    qos.resource_limits().max_samples_per_instance = q.depth;
    qos.resource_limits().max_samples = instances * q.depth;
  }
  // Reuse sample buffers instead of allocating per write; data sharing between processes on
  // one host (bounded types) so frames are not copied through a socket.
  qos.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  qos.data_sharing().automatic();
  return qos;
}

}  // namespace

DataWriterQos writer_qos(const Qos& q, int instances) { return endpoint_qos(DATAWRITER_QOS_DEFAULT, q, instances); }

DataReaderQos reader_qos(const Qos& q, int instances) { return endpoint_qos(DATAREADER_QOS_DEFAULT, q, instances); }

void set_latency_budget(DataReaderQos& qos, std::chrono::nanoseconds budget) {
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(budget);
  qos.latency_budget().duration = eprosima::fastrtps::Duration_t(
      static_cast<std::int32_t>(seconds.count()), static_cast<std::uint32_t>((budget - seconds).count()));
  qos.latency_budget().hasChanged = true;  // else discovery leaves it out and readers see zero
}

std::string qos_policy_name(int policy_id) {
  switch (policy_id) {
    case DURABILITY_QOS_POLICY_ID: return "DURABILITY";
    case PRESENTATION_QOS_POLICY_ID: return "PRESENTATION";
    case DEADLINE_QOS_POLICY_ID: return "DEADLINE";
    case LATENCYBUDGET_QOS_POLICY_ID: return "LATENCY_BUDGET";
    case OWNERSHIP_QOS_POLICY_ID: return "OWNERSHIP";
    case LIVELINESS_QOS_POLICY_ID: return "LIVELINESS";
    case PARTITION_QOS_POLICY_ID: return "PARTITION";
    case RELIABILITY_QOS_POLICY_ID: return "RELIABILITY";
    case DESTINATIONORDER_QOS_POLICY_ID: return "DESTINATION_ORDER";
    case DATAREPRESENTATION_QOS_POLICY_ID: return "DATA_REPRESENTATION";
    case TYPECONSISTENCYENFORCEMENT_QOS_POLICY_ID: return "TYPE_CONSISTENCY_ENFORCEMENT";
    case DISABLEPOSITIVEACKS_QOS_POLICY_ID: return "DISABLE_POSITIVE_ACKS";
    default: return "QoS policy " + std::to_string(policy_id);
  }
}

std::string incompatibility(int policy_id, const Qos& ours, bool writer) {
  const std::string name = qos_policy_name(policy_id);
  // Only an offer weaker than the request fails: the reader asks for more than the writer gives.
  if (policy_id == RELIABILITY_QOS_POLICY_ID)
    return name + (writer ? ": a reader wants reliable, this writer offers " : ": this reader wants ") +
           (writer ? (ours.reliability == Reliability::kReliable ? "reliable" : "best effort")
                   : std::string(ours.reliability == Reliability::kReliable ? "reliable" : "best effort") +
                         ", the writer offers best effort");
  if (policy_id == DURABILITY_QOS_POLICY_ID)
    return name + (writer ? ": a reader wants transient-local, this writer offers volatile"
                          : ": this reader wants transient-local, the writer offers volatile");
  if (policy_id == DEADLINE_QOS_POLICY_ID)
    return name +
           (writer ? ": a reader wants a shorter deadline than this writer's "
                   : ": this reader's deadline is shorter than the writer's; this reader's is ") +
           (ours.deadline_ns > 0 ? std::to_string(ours.deadline_ns / 1000) + " us" : "none");
  if (policy_id == OWNERSHIP_QOS_POLICY_ID)
    return name + (ours.single_writer ? ": this topic takes one writer (exclusive ownership), the other side shares it"
                                      : ": the other side takes one writer (exclusive ownership), this one shares it");
  if (policy_id == LIVELINESS_QOS_POLICY_ID && ours.single_writer)
    return name +
           (writer ? ": a reader asks for a shorter liveliness lease than this writer's "
                   : ": this one-writer topic's reader asks for a liveliness lease of ") +
           std::to_string(kOneWriterLiveliness.count()) + " ms" +
           (writer ? "" : ", the writer asserts it less often (or not at all)");
  return name + ": the two endpoints' settings cannot match";
}

}  // namespace wysiwyf::dds
