#pragma once
// A DDS participant of a test's own, outside any pipeline: plain (an intruder) or with one of a
// security policy's identities, writing any message type with the pipeline's own QoS.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <optional>
#include <string>

#include "raw_cdr_type.hpp"  // apps/wysiwyf
#include "wysiwyf/dds.hpp"
#include "wysiwyf/dds_security.hpp"
#include "wysiwyf/message_traits.hpp"

namespace wysiwyf::test {

// A DDS participant of the test's own: plain (an intruder) or with one of the policy's identities.
namespace intruder {
using namespace eprosima::fastdds::dds;

class Participant {
 public:
  Participant(int domain, const std::optional<dds::SecurityIdentity>& identity, const std::string& name = "intruder") {
    DomainParticipantQos qos = dds::participant_qos("loopback", name);
    if (identity) dds::enable_security(qos, *identity);
    participant_ = DomainParticipantFactory::get_instance()->create_participant(domain, qos);
    if (!participant_) return;
    publisher_ = participant_->create_publisher(PUBLISHER_QOS_DEFAULT);
  }
  ~Participant() {
    if (!participant_) return;
    participant_->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
  bool ok() const { return participant_ != nullptr; }

  // `strength` >= 0: a writer that declares itself the one writer of a topic (exclusive ownership,
  // its liveliness lease) with that strength, stronger than the pipeline's; otherwise DDS's
  // default, shared ownership. `deadline_ns` > 0: it offers that deadline (a reader with one
  // matches only a writer that offers as much).
  template <class T>
  DataWriter* writer(const std::string& topic, int strength = -1, std::int64_t deadline_ns = 0) {
    Qos declared = Qos::reliable(8);
    declared.single_writer = strength >= 0;
    declared.deadline_ns = deadline_ns;
    DataWriterQos qos = dds::writer_qos(declared);
    qos.data_sharing().off();  // over the network path, as the pipeline's loopback transport
    if (strength >= 0) qos.ownership_strength().value = static_cast<std::uint32_t>(strength);
    return publisher_->create_datawriter(this->topic<T>(topic), qos);
  }

  // A writer of raw CDR bytes (cli::RawCdr, the recorder's and player's type) under `type_name`,
  // of samples of any size (beyond the type's own bound if the test says so), with the same QoS
  // choices as writer(): what a participant with its own idea of the type, or none, may send.
  DataWriter* raw_writer(const std::string& topic, const std::string& type_name, std::int64_t deadline_ns = 0) {
    TypeSupport type(new cli::RawCdrType(type_name, false));
    if (!participant_->find_type(type_name)) type.register_type(participant_);
    Topic* t = participant_->create_topic(topic, type_name, TOPIC_QOS_DEFAULT);
    Qos declared = Qos::reliable(8);
    declared.deadline_ns = deadline_ns;
    DataWriterQos qos = dds::writer_qos(declared);
    qos.data_sharing().off();
    return t ? publisher_->create_datawriter(t, qos) : nullptr;
  }

 private:
  template <class T>
  Topic* topic(const std::string& name) {
    TypeSupport type(MessageTraits<T>::make_type());
    type->auto_fill_type_object(false);
    type->auto_fill_type_information(false);
    if (!participant_->find_type(type.get_type_name())) type.register_type(participant_);
    if (auto* t = participant_->find_topic(name, eprosima::fastrtps::Duration_t(0, 0))) return t;
    return participant_->create_topic(name, type.get_type_name(), TOPIC_QOS_DEFAULT);
  }
  DomainParticipant* participant_ = nullptr;
  Publisher* publisher_ = nullptr;
};

}  // namespace intruder
using intruder::Participant;

}  // namespace wysiwyf::test
