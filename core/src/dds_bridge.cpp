// The bridge itself: the participant, a topic's writer link, the publisher thread, connect and health.
#include "dds_bridge.hpp"
#include "dds_bridge_listeners.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "wysiwyf/dds.hpp"
#include "wysiwyf/dds_log.hpp"
#include "wysiwyf/dds_discovery.hpp"
#include "wysiwyf/stale_shared_memory.hpp"

namespace wysiwyf::detail {

using namespace eprosima::fastdds::dds;

namespace {

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
        one_writer(c.one_writer()),
        buffer(c.create_sample()) {
    DataWriterQos qos = dds::writer_qos(endpoint_qos(c.writer_qos(), c), instances);
    if (!b.data_sharing_) qos.data_sharing().off();
    qos.user_data().data_vec(dds::endpoint_ports_user_data({c.local_writers(), c.local_readers()}));
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
    for (; channel.take_outgoing(buffer); ++sent)
      if (!writer->write(buffer) && counters.lost.fetch_add(1) == 0)  // (counted in health() as lost)
        bridge.say("topic '" + channel.topic() +
                   "': DDS refused to send a sample to other processes; further refusals are counted");
    return sent;
  }

  // Publisher thread: a one-writer topic's writer tells its readers it lives, whether it wrote or
  // not (dds::kOneWriterLiveliness), every lease / dds::kOneWriterAssertions.
  void assert_liveliness_if_due(Doorbell::Clock::time_point now) {
    if (!one_writer || now < next_assertion) return;
    writer->assert_liveliness();
    next_assertion = now + dds::kOneWriterLiveliness / dds::kOneWriterAssertions;
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
  const bool one_writer;
  Doorbell::Clock::time_point next_assertion{};  // (publisher thread)
  void* buffer;                                  // the sample being sent
  DataWriter* writer = nullptr;
  std::atomic<int> matched{0};
  std::atomic<bool> pending{false};
  std::mutex prompt_mutex;
  std::set<InstanceHandle_t> prompt_readers;  // matched readers that want each sample as it is written
  std::atomic<int> prompt{0};                 // their number
  Counters counters;
};

DdsBridge::DdsBridge(const DdsParticipantOptions& o, std::function<void(const std::string&)> report)
    : writer_participants_(o.writer_participants),
      report_(std::move(report)),
      data_sharing_(dds::uses_data_sharing(o.transport)) {
  dds::route_fast_dds_log();  // (Fast DDS's own messages: once each, then counted)
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
      const auto now = Doorbell::Clock::now();
      std::lock_guard<std::mutex> lock(writers_mutex_);
      for (auto& link : writers_) {
        sent += link->drain();
        link->assert_liveliness_if_due(now);
      }
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
    if (const auto it = writer_participants_.find(channel.topic()); it != writer_participants_.end())
      link->expected_writer = it->second;
    DataReaderQos qos = dds::reader_qos(endpoint_qos(channel.reader_qos(), channel), instances);
    if (!data_sharing_) qos.data_sharing().off();
    qos.user_data().data_vec(dds::endpoint_ports_user_data({0, channel.local_readers()}));
    if (!subscriber_->create_datareader(topic, qos, link.get(),
                                        StatusMask::data_available()
                                            << StatusMask::requested_incompatible_qos() << StatusMask::sample_lost()
                                            << StatusMask::subscription_matched()
                                            << StatusMask::requested_deadline_missed()
                                            << StatusMask::liveliness_changed()))
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
