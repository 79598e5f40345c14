#include "wysiwyf/detail/topic_channel.hpp"

#include <fastdds/dds/topic/TopicDataType.hpp>

#include <memory>

namespace wysiwyf::detail {

std::uint32_t TopicChannelBase::max_serialized_size() const {
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type(make_type_());
  return type->m_typeSize;
}

}  // namespace wysiwyf::detail
