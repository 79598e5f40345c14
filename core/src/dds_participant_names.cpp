// Who is who on the domain: participants' names (a lost or departed process of the pipeline is said), batch readers.
#include "dds_bridge_listeners.hpp"

#include <sstream>

#include "wysiwyf/dds.hpp"

namespace wysiwyf::detail {

using namespace eprosima::fastdds::dds;

void DdsBridge::ParticipantNames::on_participant_discovery(DomainParticipant*,
                                                           eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) {
  using S = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo::DISCOVERY_STATUS;
  const std::string name = info.info.m_participantName.to_string();
  {
    std::lock_guard<std::mutex> lock(mutex);
    names[info.info.m_guid.guidPrefix] = name;
  }
  if (name.rfind(pipeline_prefix, 0) != 0) return;
  if (info.status == S::DROPPED_PARTICIPANT)
    bridge.say("process '" + name + "' is lost: nothing heard from it for its DDS lease (" +
               std::to_string(dds::kLeaseSeconds) + " s); its writers are unmatched");
  else if (info.status == S::REMOVED_PARTICIPANT)
    bridge.say("process '" + name + "' left the domain");
}

void DdsBridge::ParticipantNames::on_subscriber_discovery(DomainParticipant*,
                                                          eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) {
  using S = eprosima::fastrtps::rtps::ReaderDiscoveryInfo::DISCOVERY_STATUS;
  const auto& budget = info.info.m_qos.m_latencyBudget.duration;
  const bool batches =
      info.status != S::REMOVED_READER && budget.to_ns() >= std::chrono::nanoseconds(dds::kBatchingPeriod).count();
  std::lock_guard<std::mutex> lock(mutex);
  if (batches)
    batch_readers.insert(info.info.guid());
  else
    batch_readers.erase(info.info.guid());
}

bool DdsBridge::takes_batches(const InstanceHandle_t& reader) const {
  eprosima::fastrtps::rtps::GUID_t guid;
  eprosima::fastrtps::rtps::iHandle2GUID(guid, reader);
  std::lock_guard<std::mutex> lock(names_->mutex);
  return names_->batch_readers.count(guid) != 0;
}

std::string DdsBridge::process_name(const InstanceHandle_t& handle) const {
  eprosima::fastrtps::rtps::GUID_t guid;
  eprosima::fastrtps::rtps::iHandle2GUID(guid, handle);
  std::lock_guard<std::mutex> lock(names_->mutex);
  const auto it = names_->names.find(guid.guidPrefix);
  return it != names_->names.end() ? it->second : std::string();
}

std::string DdsBridge::writer_name(const InstanceHandle_t& handle) const {
  eprosima::fastrtps::rtps::GUID_t guid;
  eprosima::fastrtps::rtps::iHandle2GUID(guid, handle);
  std::ostringstream id;
  id << guid;
  const std::string process = process_name(handle);
  return !process.empty() ? "'" + process + "' (writer " + id.str() + ")" : "writer " + id.str();
}

}  // namespace wysiwyf::detail
