#pragma once
// Message types by DDS type name, for tools that meet a topic they know only by name
// (`wysiwyf topic echo`): make its TypeSupport, and print a sample as YAML.
#include <functional>
#include <map>
#include <string>

#include "wysiwyf/message_traits.hpp"

namespace wysiwyf {

struct MessageType {
  std::string name;
  eprosima::fastdds::dds::TopicDataType* (*make_type)() = nullptr;
  std::function<std::string(const void*)> to_yaml;
};

class MessageRegistry {
 public:
  template <class T>
  void add(std::string (*printer)(const T&)) {
    MessageType m;
    m.name = MessageTraits<T>::type_name();
    m.make_type = &MessageTraits<T>::make_type;
    m.to_yaml = [printer](const void* sample) { return printer(*static_cast<const T*>(sample)); };
    types_[m.name] = std::move(m);
  }
  const MessageType* find(const std::string& name) const {
    auto it = types_.find(name);
    return it == types_.end() ? nullptr : &it->second;
  }
  const std::map<std::string, MessageType>& all() const { return types_; }

 private:
  std::map<std::string, MessageType> types_;
};

}  // namespace wysiwyf
