#include "dds_bridge.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "wysiwyf/dds.hpp"
#include "wysiwyf/dds_discovery.hpp"
#include "wysiwyf/stale_shared_memory.hpp"

namespace wysiwyf::detail {

using namespace eprosima::fastdds::dds;

namespace {

// Counts what DDS reports for one endpoint; read by health() from another thread.
struct Counters {
  std::atomic<std::uint64_t> incompatible{0};
  std::atomic<int> last_policy{0};
  std::atomic<std::uint64_t> lost{0};
  std::atomic<std::uint64_t> ignored{0};          // samples of a writer that does not own a one-writer topic
  std::atomic<std::uint64_t> deadline_missed{0};  // reader: periods of its deadline without a sample
};

// The channel's QoS for its DDS endpoints: a one-writer topic is one for writers and readers alike.
Qos endpoint_qos(Qos q, const TopicChannelBase& channel) {
  q.single_writer = channel.one_writer();
  return q;
}

}  // namespace

struct DdsBridge::WriterLink final : public DdsWriterLink, public DataWriterListener {
  WriterLink(DdsBridge& b, TopicChannelBase& c, Topic* topic, int instances)
      : bridge(b),
        channel(c),
        always(c.writer_qos().durability == Durability::kTransientLocal),
        buffer(c.create_sample()) {
    DataWriterQos qos = dds::writer_qos(endpoint_qos(c.writer_qos(), c), instances);
    if (!b.data_sharing_) qos.data_sharing().off();
    writer = b.publisher_->create_datawriter(
        topic, qos, this, StatusMask::publication_matched() << StatusMask::offered_incompatible_qos());
    if (!writer)
      throw std::runtime_error("cannot create a DDS writer for topic '" + topic->get_name() + "'" +
                               b.refused_by_permissions("publish"));
  }
  ~WriterLink() override { channel.delete_sample(buffer); }

  bool wanted() const override { return always || matched.load(std::memory_order_relaxed) > 0; }
  void queued(std::size_t waiting, std::size_t capacity) override {
    pending.store(true, std::memory_order_release);
    // The publisher is woken after this tick unless every reader takes batches and the outbox
    // has room for one: then after the tick that ends a batching period (flush_batch_if_due).
    if (!bridge.batching_.load(std::memory_order_relaxed) || prompt.load(std::memory_order_relaxed) > 0 ||
        2 * waiting > capacity)
      bridge.dirty_.store(true, std::memory_order_release);
    else
      bridge.batched_.store(true, std::memory_order_release);
  }
  // Publisher thread: sends what waits in the outbox; how many.
  std::uint64_t drain() {
    if (!pending.exchange(false, std::memory_order_acq_rel)) return 0;
    std::uint64_t sent = 0;
    for (; channel.take_outgoing(buffer); ++sent) writer->write(buffer);
    return sent;
  }

  void on_publication_matched(DataWriter*, const PublicationMatchedStatus& status) override {
    matched.store(status.current_count, std::memory_order_relaxed);
    std::lock_guard<std::mutex> lock(prompt_mutex);
    if (status.current_count_change > 0 && !bridge.takes_batches(status.last_subscription_handle))
      prompt_readers.insert(status.last_subscription_handle);
    else if (status.current_count_change < 0)
      prompt_readers.erase(status.last_subscription_handle);
    prompt.store(static_cast<int>(prompt_readers.size()), std::memory_order_relaxed);
  }
  void on_offered_incompatible_qos(DataWriter*, const OfferedIncompatibleQosStatus& status) override {
    counters.incompatible.fetch_add(1);
    counters.last_policy.store(status.last_policy_id);
    bridge.say("topic '" + channel.topic() + "': a reader in another process was refused: " +
               dds::incompatibility(status.last_policy_id, channel.writer_qos(), true) + "; no samples flow to it");
  }

  DdsBridge& bridge;
  TopicChannelBase& channel;
  const bool always;  // transient-local: written with or without readers, for late joiners
  void* buffer;       // the sample being sent
  DataWriter* writer = nullptr;
  std::atomic<int> matched{0};
  std::atomic<bool> pending{false};
  std::mutex prompt_mutex;
  std::set<InstanceHandle_t> prompt_readers;  // matched readers that want each sample as it is written
  std::atomic<int> prompt{0};                 // their number
  Counters counters;
};

struct DdsBridge::ReaderLink final : public DataReaderListener {
  ReaderLink(DdsBridge& b, TopicChannelBase& c)
      : bridge(b), channel(c), sample(c.create_sample()), one_writer(c.one_writer()) {}
  ~ReaderLink() override { channel.delete_sample(sample); }
  void on_data_available(DataReader* reader) override {
    SampleInfo info;
    while (reader->take_next_sample(sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data || (one_writer && !follows(info.publication_handle))) continue;
      if (late.exchange(false))
        bridge.say("topic '" + channel.topic() + "': samples again from " +
                   bridge.writer_name(info.publication_handle) + " (" +
                   std::to_string(counters.deadline_missed.load()) + " deadline(s) missed so far)");
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
  // The deadline QoS (the pipeline's `qos: {port: {deadline: ..}}`): a writer whose process is
  // frozen, cut off or overloaded is named as soon as a period passes without its sample, once
  // per silence; the misses are counted (health()).
  void on_requested_deadline_missed(DataReader*, const RequestedDeadlineMissedStatus& status) override {
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
  // A one-writer topic follows the first writer it hears until that writer leaves, or, where the
  // topic has a deadline, until it misses it (DDS's ownership rule: a killed process's writer is
  // unmatched only after its lease, 5 s, and its restarted successor would wait that long). DDS
  // ownership already passes only its owner's samples, but it would hand the topic to a newcomer
  // of equal strength and lower GUID. Another writer's samples are dropped, counted and it is
  // named once.
  bool follows(const InstanceHandle_t& writer) {
    std::lock_guard<std::mutex> lock(owner_mutex);
    if (!owner) owner = writer;
    if (writer == *owner) return true;
    if (late.load()) {  // (cleared by the next sample delivered: this one)
      bridge.say("topic '" + channel.topic() + "': its writer " + bridge.writer_name(*owner) +
                 " missed its deadline; " + bridge.writer_name(writer) + " owns it now");
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
  void on_subscription_matched(DataReader*, const SubscriptionMatchedStatus& status) override {
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
  void on_requested_incompatible_qos(DataReader*, const RequestedIncompatibleQosStatus& status) override {
    counters.incompatible.fetch_add(1);
    counters.last_policy.store(status.last_policy_id);
    bridge.say("topic '" + channel.topic() + "': a writer in another process was refused: " +
               dds::incompatibility(status.last_policy_id, channel.reader_qos(), false) + "; no samples come from it");
  }
  void on_sample_lost(DataReader*, const SampleLostStatus& status) override {
    // Said once; then counted (health(), the diagnostics).
    if (counters.lost.exchange(static_cast<std::uint64_t>(status.total_count)) == 0)
      bridge.say("topic '" + channel.topic() + "': DDS lost samples on the way in (" +
                 std::to_string(status.total_count) + " so far; further losses are counted)");
  }
  DdsBridge& bridge;
  TopicChannelBase& channel;
  void* sample;
  const bool one_writer;
  std::mutex owner_mutex;  // the receive, discovery and event threads
  std::optional<InstanceHandle_t> owner;
  std::set<InstanceHandle_t> named;             // the writers said to be ignored
  std::atomic<bool> late{false};                // a deadline passed without a sample, and none came since
  std::optional<InstanceHandle_t> last_writer;  // whose sample came last (owner_mutex)
  const std::string* origin_ = nullptr;         // its process's name, interned (owner_mutex)
  Counters counters;
};

// Who is who on the domain: participants' names by their GUID prefix, for messages that name a writer.
// A process of the same pipeline ("<pipeline>/<group>...") that leaves or goes silent is said.
struct DdsBridge::ParticipantNames final : public DomainParticipantListener {
  ParticipantNames(DdsBridge& b, std::string pipeline) : bridge(b), pipeline_prefix(std::move(pipeline) + "/") {}
  void on_participant_discovery(DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override {
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
  // Readers that declared a latency budget of dds::kBatchingPeriod or more (Fast DDS announces a
  // reader before it matches any writer of ours).
  void on_subscriber_discovery(DomainParticipant*, eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override {
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
  DdsBridge& bridge;
  const std::string pipeline_prefix;
  std::mutex mutex;
  std::map<eprosima::fastrtps::rtps::GuidPrefix_t, std::string> names;
  std::set<eprosima::fastrtps::rtps::GUID_t> batch_readers;
};

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

DdsBridge::DdsBridge(const DdsParticipantOptions& o, std::function<void(const std::string&)> report)
    : report_(std::move(report)), data_sharing_(dds::uses_data_sharing(o.transport)) {
  auto* factory = DomainParticipantFactory::get_instance();
  if (!o.profiles_file.empty() && factory->load_XML_profiles_file(o.profiles_file) != ReturnCode_t::RETCODE_OK)
    throw std::runtime_error("cannot load Fast DDS XML profiles from '" + o.profiles_file + "'");
  DomainParticipantQos qos;
  if (!o.participant_profile.empty()) {
    if (factory->get_participant_qos_from_profile(o.participant_profile, qos) != ReturnCode_t::RETCODE_OK)
      throw std::runtime_error("no participant profile '" + o.participant_profile + "' in '" + o.profiles_file + "'");
  } else {
    qos = dds::participant_qos(o.transport, o.name);
    dds::remove_stale_shared_memory_once(o.transport, [this](const std::string& s) { say(s); });
  }
  if (!o.discovery_servers.empty()) dds::use_discovery_servers(qos, o.discovery_servers, /*see_everything=*/false);
  if (o.security) {
    dds::enable_security(qos, *o.security);
    identity_ = o.security->identity;
  }
  names_ = std::make_unique<ParticipantNames>(*this, o.name.substr(0, o.name.find('/')));
  participant_ = factory->create_participant(o.domain, qos, names_.get(), StatusMask::none());
  if (!participant_)
    throw std::runtime_error(
        "cannot create a DDS participant on domain " + std::to_string(o.domain) +
        (o.participant_profile.empty() ? "" : " with profile '" + o.participant_profile + "'") +
        (o.security ? " as DDS-Security identity '" + o.security->identity + "' of '" + o.security->keys_dir +
                          "' (Fast DDS refused its certificate, key or signed documents: see its log above)"
                    : ""));
  publisher_ = participant_->create_publisher(PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
}

std::string DdsBridge::refused_by_permissions(const std::string& action) const {
  if (identity_.empty()) return "";
  return ": DDS-Security identity '" + identity_ + "' may not " + action +
         " it (its permissions document, made by scripts/security from the policy)";
}

void DdsBridge::stop_publishing() {
  if (!publisher_thread_.joinable()) return;
  bell_.stop();
  publisher_thread_.join();  // it sends what is still waiting first
}

DdsBridge::~DdsBridge() {
  stop_publishing();
  for (auto& w : writers_) w->channel.set_dds_writer(nullptr);  // a later write stays local
  if (!participant_) return;
  participant_->delete_contained_entities();  // readers stop calling their listeners here
  DomainParticipantFactory::get_instance()->delete_participant(participant_);
  readers_.clear();
  writers_.clear();
}

void DdsBridge::flush_batch_if_due() {
  const std::int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Doorbell::Clock::now().time_since_epoch()).count();
  std::int64_t due = next_batch_ns_.load(std::memory_order_relaxed);
  if (now < due) return;
  const std::int64_t next = now + std::chrono::nanoseconds(dds::kBatchingPeriod).count();
  if (!next_batch_ns_.compare_exchange_strong(due, next, std::memory_order_relaxed)) return;  // another thread rang
  batched_.store(false, std::memory_order_relaxed);
  bell_.ring();
}

void DdsBridge::publish_loop() {
  using Wake = Doorbell::Wake;
  Doorbell::Clock::time_point rang;
  while (true) {
    const Wake w = bell_.wait(rang, Doorbell::Clock::now() + kIdleFlush);
    if (w != Wake::kRang) {  // (drained below either way)
      dirty_.store(false, std::memory_order_relaxed);
      batched_.store(false, std::memory_order_relaxed);
    }
    std::uint64_t sent = 0;
    {
      std::lock_guard<std::mutex> lock(writers_mutex_);
      for (auto& link : writers_) sent += link->drain();
    }
    if (sent > 0) {
      samples_sent_.fetch_add(sent, std::memory_order_relaxed);
      wakes_that_sent_.fetch_add(1, std::memory_order_relaxed);
    }
    if (w == Wake::kStopped) return;
  }
}

void DdsBridge::connect(TopicChannelBase& channel) {
  TypeSupport type(channel.make_type());
  // Endpoints announce the type by name only: a process that has type objects registered (a tool
  // that loaded message libraries) would otherwise send them in discovery, and Fast DDS 2.9's
  // readers of them crash building sequence types (TypeObjectFactory::get_sequence_identifier).
  type->auto_fill_type_object(false);
  type->auto_fill_type_information(false);
  if (!participant_->find_type(channel.type_name())) type.register_type(participant_);
  const int instances = type->m_isGetKeyDefined ? dds::kKeyedTopicInstances : 1;
  Topic* topic = participant_->create_topic(channel.topic(), channel.type_name(), TOPIC_QOS_DEFAULT);
  if (!topic)
    throw std::runtime_error("cannot create DDS topic '" + channel.topic() + "' of type " + channel.type_name());
  if (channel.local_writers() > 0) {
    auto link = std::make_unique<WriterLink>(*this, channel, topic, instances);
    WriterLink* raw = link.get();
    {
      std::lock_guard<std::mutex> lock(writers_mutex_);
      writers_.push_back(std::move(link));
    }
    channel.set_dds_writer(raw);
    if (!publisher_thread_.joinable()) publisher_thread_ = std::thread([this] { publish_loop(); });
  } else if (channel.local_readers() > 0) {
    auto link = std::make_unique<ReaderLink>(*this, channel);
    DataReaderQos qos = dds::reader_qos(endpoint_qos(channel.reader_qos(), channel), instances);
    if (!data_sharing_) qos.data_sharing().off();
    if (!subscriber_->create_datareader(topic, qos, link.get(),
                                        StatusMask::data_available()
                                            << StatusMask::requested_incompatible_qos() << StatusMask::sample_lost()
                                            << StatusMask::subscription_matched()
                                            << StatusMask::requested_deadline_missed()))
      throw std::runtime_error("cannot create a DDS reader for topic '" + channel.topic() + "'" +
                               refused_by_permissions("subscribe to"));
    readers_.push_back(std::move(link));
  }
}

std::vector<DdsTopicHealth> DdsBridge::health() const {
  std::vector<DdsTopicHealth> out;
  auto add = [&](const TopicChannelBase& channel, const Counters& c, std::uint64_t outbox_dropped) {
    const std::uint64_t incompatible = c.incompatible.load();
    if (incompatible == 0 && c.lost.load() == 0 && outbox_dropped == 0 && c.ignored.load() == 0 &&
        c.deadline_missed.load() == 0)
      return;
    out.push_back(DdsTopicHealth{channel.topic(), incompatible,
                                 incompatible ? dds::qos_policy_name(c.last_policy.load()) : "", c.lost.load(),
                                 outbox_dropped, c.ignored.load(), c.deadline_missed.load()});
  };
  {
    std::lock_guard<std::mutex> lock(writers_mutex_);
    for (const auto& w : writers_) add(w->channel, w->counters, w->channel.outgoing_dropped());
  }
  for (const auto& r : readers_) add(r->channel, r->counters, 0);
  return out;
}

}  // namespace wysiwyf::detail
