#pragma once
// All topics of one process, by name. Two ports of different types on one topic are refused.
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "wysiwyf/detail/topic_channel.hpp"

namespace wysiwyf::detail {

class TopicBus {
 public:
  // The channel for `topic`, created on first use. `port` names the asking port for the error.
  template <class T>
  TopicChannel<T>* channel(const std::string& topic, const std::string& port) {
    auto it = channels_.find(topic);
    if (it == channels_.end()) {
      auto created = std::make_unique<TopicChannel<T>>(topic);
      auto* raw = created.get();
      channels_.emplace(topic, std::move(created));
      owners_[topic] = port;
      return raw;
    }
    auto* typed = dynamic_cast<TopicChannel<T>*>(it->second.get());
    if (!typed)
      throw std::runtime_error("topic '" + topic + "': port " + port + " carries " + MessageTraits<T>::type_name() +
                               " but port " + owners_[topic] + " carries " + it->second->type_name());
    return typed;
  }

  const std::map<std::string, std::unique_ptr<TopicChannelBase>>& channels() const { return channels_; }

 private:
  std::map<std::string, std::unique_ptr<TopicChannelBase>> channels_;
  std::map<std::string, std::string> owners_;  // topic -> first port that used it
};

}  // namespace wysiwyf::detail
