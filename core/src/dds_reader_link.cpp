// A topic's reader: its samples into the local queues, one-writer topics, deadlines, and what DDS reports.
#include "dds_bridge_listeners.hpp"

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "wysiwyf/dds.hpp"

namespace wysiwyf::detail {

using namespace eprosima::fastdds::dds;

DdsBridge::ReaderLink::ReaderLink(DdsBridge& b, TopicChannelBase& c)
    : bridge(b), channel(c), sample(c.create_sample()), one_writer(c.one_writer()) {}

DdsBridge::ReaderLink::~ReaderLink() { channel.delete_sample(sample); }

void DdsBridge::ReaderLink::on_data_available(DataReader* reader) {
  SampleInfo info;
  while (reader->take_next_sample(sample, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data || (one_writer && !follows(info.publication_handle))) continue;
    if (late.exchange(false))
      bridge.say("topic '" + channel.topic() + "': samples again from " + bridge.writer_name(info.publication_handle) +
                 " (" + std::to_string(counters.deadline_missed.load()) + " deadline(s) missed so far)");
    const std::string* origin = nullptr;
    {
      std::lock_guard<std::mutex> lock(owner_mutex);
      // The writing process's name, looked up when the writer changes (not per sample).
      if (!origin_ || last_writer != info.publication_handle) {
        const std::string process = bridge.process_name(info.publication_handle);
        origin_ = process.empty() ? nullptr : channel.intern_origin(process);  // (unknown yet: again)
      }
      last_writer = info.publication_handle;
      origin = origin_;
    }
    channel.deliver_from_dds(sample, origin);
  }
}

void DdsBridge::ReaderLink::on_requested_deadline_missed(DataReader*, const RequestedDeadlineMissedStatus& status) {
  counters.deadline_missed.store(static_cast<std::uint64_t>(status.total_count));
  if (late.exchange(true)) return;
  std::optional<InstanceHandle_t> writer;
  {
    std::lock_guard<std::mutex> lock(owner_mutex);
    writer = last_writer;
  }
  bridge.say("topic '" + channel.topic() + "': no sample for its deadline (" +
             std::to_string(channel.reader_qos().deadline_ns / 1'000'000) + " ms) from " +
             (writer ? bridge.writer_name(*writer) : std::string("any writer")) +
             ": is its process frozen, cut off or overloaded?");
}

bool DdsBridge::ReaderLink::follows(const InstanceHandle_t& writer) {
  std::lock_guard<std::mutex> lock(owner_mutex);
  if (owner && writer == *owner) return true;  // (admitted below when it became the owner)
  if (!expected_writer.empty()) {
    // (A writer whose participant is not discovered yet has no name: refused until it has one.)
    const std::string process = bridge.process_name(writer);
    const bool ours = process == expected_writer || process.rfind(expected_writer + "/", 0) == 0;
    if (!ours) {
      counters.ignored.fetch_add(1);
      if (!process.empty() && named.insert(writer).second)
        bridge.say("topic '" + channel.topic() + "': samples of " + bridge.writer_name(writer) +
                   " are refused: its one writer is process group '" + expected_writer +
                   "' of this pipeline, and no other participant may take it over");
      return false;
    }
  }
  if (!owner) {
    owner = writer;
    return true;
  }
  if (late.load()) {  // (cleared by the next sample delivered: this one)
    bridge.say("topic '" + channel.topic() + "': its writer " + bridge.writer_name(*owner) + " missed its deadline; " +
               bridge.writer_name(writer) + " owns it now");
    owner = writer;
    named.erase(writer);
    return true;
  }
  counters.ignored.fetch_add(1);
  if (named.insert(writer).second)  // (the name is made once per writer, not per sample)
    bridge.say("topic '" + channel.topic() + "': samples of a second writer, " + bridge.writer_name(writer) +
               ", are ignored: the topic takes one writer, and " + bridge.writer_name(*owner) + " is it");
  return false;
}

void DdsBridge::ReaderLink::on_subscription_matched(DataReader*, const SubscriptionMatchedStatus& status) {
  if (!one_writer) return;
  const std::string name = bridge.writer_name(status.last_publication_handle);
  std::lock_guard<std::mutex> lock(owner_mutex);
  if (status.current_count_change > 0 && status.current_count > 1)
    bridge.say("topic '" + channel.topic() + "' takes one writer, and another one matched: " + name +
               " (writers now: " + std::to_string(status.current_count) + "); only the first heard is followed" +
               (owner ? ", " + bridge.writer_name(*owner) : ""));
  if (status.current_count_change < 0 && owner && status.last_publication_handle == *owner) {
    bridge.say("topic '" + channel.topic() + "': its writer " + name + " left; the next writer heard owns it");
    owner.reset();
  }
}

void DdsBridge::ReaderLink::on_liveliness_changed(DataReader*, const LivelinessChangedStatus& status) {
  if (!one_writer || status.not_alive_count_change <= 0) return;
  std::lock_guard<std::mutex> lock(owner_mutex);
  if (!owner || status.last_publication_handle != *owner) return;
  bridge.say("topic '" + channel.topic() + "': its writer " + bridge.writer_name(*owner) +
             " lost its liveliness (nothing from its process for " + std::to_string(dds::kOneWriterLiveliness.count()) +
             " ms); the next writer heard owns it");
  owner.reset();
}

void DdsBridge::ReaderLink::on_requested_incompatible_qos(DataReader*, const RequestedIncompatibleQosStatus& status) {
  counters.incompatible.fetch_add(1);
  counters.last_policy.store(status.last_policy_id);
  bridge.say("topic '" + channel.topic() + "': a writer in another process was refused: " +
             dds::incompatibility(status.last_policy_id, channel.reader_qos(), false) + "; no samples come from it");
}

void DdsBridge::ReaderLink::on_sample_lost(DataReader*, const SampleLostStatus& status) {
  // Said once; then counted (health(), the diagnostics).
  if (counters.lost.exchange(static_cast<std::uint64_t>(status.total_count)) == 0)
    bridge.say("topic '" + channel.topic() + "': DDS lost samples on the way in (" +
               std::to_string(status.total_count) + " so far; further losses are counted)");
}

}  // namespace wysiwyf::detail
