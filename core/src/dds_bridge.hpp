#pragma once
// Carries a process's topics over Fast DDS: a DataWriter for every topic a local component
// publishes (so other processes and monitors see it), a DataReader for every topic local
// components read but no local component publishes.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>

#include <memory>
#include <string>
#include <vector>

#include "wysiwyf/detail/topic_channel.hpp"

namespace wysiwyf::detail {

class DdsBridge {
 public:
  DdsBridge(int domain, const std::string& transport, const std::string& profiles_file,
            const std::string& participant_profile, const std::string& participant_name);
  ~DdsBridge();
  DdsBridge(const DdsBridge&) = delete;
  DdsBridge& operator=(const DdsBridge&) = delete;

  void connect(TopicChannelBase& channel);

 private:
  struct ReaderLink;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::vector<std::unique_ptr<ReaderLink>> readers_;
};

}  // namespace wysiwyf::detail
