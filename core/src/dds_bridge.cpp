#include "dds_bridge.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <atomic>
#include <stdexcept>

#include "wysiwyf/dds.hpp"

namespace wysiwyf::detail {

using namespace eprosima::fastdds::dds;

namespace {

// Writes only while a reader is matched: an unwatched topic costs no serialisation. Transient-
// local topics always write, so a late reader still gets the last samples.
class WriterLink final : public DdsWriterLink, public DataWriterListener {
 public:
  WriterLink(Publisher* publisher, Topic* topic, const Qos& qos)
      : always_(qos.durability == Durability::kTransientLocal) {
    writer_ = publisher->create_datawriter(topic, dds::writer_qos(qos), this, StatusMask::publication_matched());
    if (!writer_) throw std::runtime_error("cannot create a DDS writer for topic '" + topic->get_name() + "'");
  }
  void write(const void* sample) override {
    if (always_ || matched_.load(std::memory_order_relaxed) > 0) writer_->write(const_cast<void*>(sample));
  }
  void on_publication_matched(DataWriter*, const PublicationMatchedStatus& status) override {
    matched_.store(status.current_count, std::memory_order_relaxed);
  }

 private:
  DataWriter* writer_ = nullptr;
  bool always_;
  std::atomic<int> matched_{0};
};

}  // namespace

struct DdsBridge::ReaderLink final : public DataReaderListener {
  ReaderLink(TopicChannelBase& c) : channel(c), sample(c.create_sample()) {}
  ~ReaderLink() override { channel.delete_sample(sample); }
  void on_data_available(DataReader* reader) override {
    SampleInfo info;
    while (reader->take_next_sample(sample, &info) == ReturnCode_t::RETCODE_OK)
      if (info.valid_data) channel.deliver_from_dds(sample);
  }
  TopicChannelBase& channel;
  void* sample;
};

DdsBridge::DdsBridge(int domain, const std::string& transport, const std::string& profiles_file,
                     const std::string& participant_profile, const std::string& participant_name) {
  auto* factory = DomainParticipantFactory::get_instance();
  if (!profiles_file.empty() && factory->load_XML_profiles_file(profiles_file) != ReturnCode_t::RETCODE_OK)
    throw std::runtime_error("cannot load Fast DDS XML profiles from '" + profiles_file + "'");
  if (!participant_profile.empty())
    participant_ = factory->create_participant_with_profile(domain, participant_profile);
  else
    participant_ = factory->create_participant(domain, dds::participant_qos(transport, participant_name));
  if (!participant_)
    throw std::runtime_error("cannot create a DDS participant on domain " + std::to_string(domain) +
                             (participant_profile.empty() ? "" : " with profile '" + participant_profile + "'"));
  publisher_ = participant_->create_publisher(PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
}

DdsBridge::~DdsBridge() {
  if (!participant_) return;
  participant_->delete_contained_entities();  // readers stop calling their listeners here
  DomainParticipantFactory::get_instance()->delete_participant(participant_);
  readers_.clear();
}

void DdsBridge::connect(TopicChannelBase& channel) {
  TypeSupport type(channel.make_type());
  // Endpoints announce the type by name only: a process that has type objects registered (a tool
  // that loaded message libraries) would otherwise send them in discovery, and Fast DDS 2.9's
  // readers of them crash building sequence types (TypeObjectFactory::get_sequence_identifier).
  type->auto_fill_type_object(false);
  type->auto_fill_type_information(false);
  if (!participant_->find_type(channel.type_name())) type.register_type(participant_);
  Topic* topic = participant_->create_topic(channel.topic(), channel.type_name(), TOPIC_QOS_DEFAULT);
  if (!topic)
    throw std::runtime_error("cannot create DDS topic '" + channel.topic() + "' of type " + channel.type_name());
  if (channel.local_writers() > 0) {
    channel.set_dds_writer(std::make_unique<WriterLink>(publisher_, topic, channel.writer_qos()));
  } else if (channel.local_readers() > 0) {
    auto link = std::make_unique<ReaderLink>(channel);
    if (!subscriber_->create_datareader(topic, dds::reader_qos(channel.reader_qos()), link.get(),
                                        StatusMask::data_available()))
      throw std::runtime_error("cannot create a DDS reader for topic '" + channel.topic() + "'");
    readers_.push_back(std::move(link));
  }
}

}  // namespace wysiwyf::detail
