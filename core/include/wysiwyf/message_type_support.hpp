#pragma once
/// @file
/// The DDS type support behind a message type's port binding, as a message library defines it
/// (`WYSIWYF_MESSAGE_TYPE_SUPPORT`, in the one .cpp that includes the generated *PubSubTypes.h):
/// fastddsgen's, with the checks a sample from any participant on the domain needs.
#include <fastcdr/exceptions/Exception.h>

#include <exception>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include "wysiwyf/message_traits.hpp"

namespace wysiwyf {

/// fastddsgen's type support `Generated`, safe against any bytes a participant sends.
template <class Generated>
class CheckedTypeSupport final : public Generated {
 public:
  /// False (the sample is dropped, as DDS drops any sample that does not deserialise) where the
  /// payload is longer than the type's bound allows, or its bytes are not the type (a boolean
  /// of 2, a sequence or string longer than the bytes left). fastddsgen's deserialize throws
  /// on these, and a throw from a reader's listener thread would end the receiving process.
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    if (payload->length > this->m_typeSize) return false;
    try {
      return Generated::deserialize(payload, data);
    } catch (const eprosima::fastcdr::exception::Exception&) {
      return false;
    } catch (const std::exception&) {  // a length that asks for more memory than there is
      return false;
    }
  }
};

}  // namespace wysiwyf

/// WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, JointState) in the message library's one .cpp that
/// includes the generated *PubSubTypes.h: the DDS type support behind the port binding.
#define WYSIWYF_MESSAGE_TYPE_SUPPORT(NS, NAME)                                           \
  eprosima::fastdds::dds::TopicDataType* wysiwyf::MessageTraits<NS::NAME>::make_type() { \
    return new wysiwyf::CheckedTypeSupport<NS::NAME##PubSubType>();                      \
  }
