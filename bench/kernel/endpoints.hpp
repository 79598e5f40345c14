#pragma once
// Two ways to move one message type between a "ping" and a "pong" topic, with the same QoS:
// raw Fast DDS (a DataWriter and a DataReader) and the kernel (Output/Input ports over the
// kernel's DDS bridge). The benchmark compares them hop for hop.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include "../../core/src/dds_bridge.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/detail/topic_bus.hpp"
#include "wysiwyf/msgs.hpp"
#include "wysiwyf/port.hpp"

namespace wysiwyf::bench {

using namespace eprosima::fastdds::dds;

template <class T>
class RawEndpoint {
 public:
  RawEndpoint(int domain, const std::string& out_topic, const std::string& in_topic, const Qos& qos) {
    participant_ = DomainParticipantFactory::get_instance()->create_participant(
        domain, dds::participant_qos("local", "bench-raw"));
    TypeSupport type(MessageTraits<T>::make_type());
    type.register_type(participant_);
    Topic* out = participant_->create_topic(out_topic, type.get_type_name(), TOPIC_QOS_DEFAULT);
    Topic* in =
        in_topic == out_topic ? out : participant_->create_topic(in_topic, type.get_type_name(), TOPIC_QOS_DEFAULT);
    writer_ = participant_->create_publisher(PUBLISHER_QOS_DEFAULT)->create_datawriter(out, dds::writer_qos(qos));
    reader_ = participant_->create_subscriber(SUBSCRIBER_QOS_DEFAULT)->create_datareader(in, dds::reader_qos(qos));
  }
  ~RawEndpoint() {
    participant_->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
  void send(const T& sample) { writer_->write(const_cast<T*>(&sample)); }
  bool poll(T& sample) {
    SampleInfo info;
    return reader_->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK && info.valid_data;
  }

 private:
  DomainParticipant* participant_ = nullptr;
  DataWriter* writer_ = nullptr;
  DataReader* reader_ = nullptr;
};

template <class T>
class KernelEndpoint {
 public:
  KernelEndpoint(int domain, const std::string& out_topic, const std::string& in_topic, const Qos& qos,
                 std::optional<dds::SecurityIdentity> security = std::nullopt)
      : bridge_(detail::DdsParticipantOptions{domain, "local", "", "", "bench-kernel", std::move(security), {}, {}}) {
    auto* out = bus_.channel<T>(out_topic, "bench.out");
    out->add_writer(qos);
    out_ = Output<T>(out);
    in_ = Input<T>(bus_.channel<T>(in_topic, "bench.in")->add_reader(qos), "bench.in");
    for (const auto& [name, channel] : bus_.channels()) bridge_.connect(*channel);
  }
  void send(const T& sample) {
    out_.write(sample);
    bridge_.flush_soon();  // as the executor does after a tick
  }
  bool poll(T& sample) { return in_.take(sample); }

 private:
  detail::TopicBus bus_;  // outlives the bridge
  detail::DdsBridge bridge_;
  Output<T> out_;
  Input<T> in_;
};

// The kernel's ports with DDS-Security on: authenticated, access-controlled, AES-GCM. Keys made
// once per run in $WYSIWYF_BENCH_KEYS: "messages" from bench/kernel/security-policy.yaml (every
// message encrypted as a whole, as shipped), "topics" from security-policy-topics.yaml (the
// ping-pong topics' submessages encrypted one by one, "clear/..." topics in clear).
template <class T, bool kPerTopic = false>
class SecuredKernelEndpoint : public KernelEndpoint<T> {
 public:
  SecuredKernelEndpoint(int domain, const std::string& out_topic, const std::string& in_topic, const Qos& qos)
      : KernelEndpoint<T>(
            domain, out_topic, in_topic, qos,
            dds::SecurityIdentity{
                std::string(std::getenv("WYSIWYF_BENCH_KEYS")) + (kPerTopic ? "/topics" : "/messages"), "bench"}) {}
};

}  // namespace wysiwyf::bench
