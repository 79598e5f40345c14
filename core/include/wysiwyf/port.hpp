#pragma once
// Typed ports. A component gets them from Context::input / Context::output in configure() and
// keeps them as members; the pipeline file maps each port to a topic.
#include <cstdint>
#include <string>

#include "wysiwyf/detail/topic_channel.hpp"
#include "wysiwyf/qos.hpp"

namespace wysiwyf {

enum class PortDirection { kInput, kOutput };

struct PortSpec {
  std::string name;
  PortDirection direction = PortDirection::kInput;
  std::string type_name;  // DDS type, e.g. "wysiwyf::msg::JointState"
  std::string description;
  Qos qos;                // the component's default; the pipeline may override it
};

// Receives samples of T. Unconnected (describe/validate mode) it never has data.
template <class T>
class Input {
 public:
  Input() = default;
  explicit Input(detail::SubscriberQueue<T>* queue) : queue_(queue) {}

  // Oldest unread sample; false when none arrived since the last read.
  bool take(T& out) { return queue_ && queue_->take(out); }
  // Newest unread sample, dropping older unread ones; false when none arrived.
  bool take_latest(T& out) { return queue_ && queue_->take_latest(out); }
  std::size_t pending() const { return queue_ ? queue_->size() : 0; }
  std::uint64_t received() const { return queue_ ? queue_->received() : 0; }
  bool connected() const { return queue_ != nullptr; }

 private:
  detail::SubscriberQueue<T>* queue_ = nullptr;
};

// Publishes samples of T to every local reader at once and to DDS.
template <class T>
class Output {
 public:
  Output() = default;
  explicit Output(detail::TopicChannel<T>* channel) : channel_(channel) {}

  void write(const T& sample) {
    if (channel_) channel_->publish(sample);
    ++written_;
  }
  std::uint64_t written() const { return written_; }
  bool connected() const { return channel_ != nullptr; }

 private:
  detail::TopicChannel<T>* channel_ = nullptr;
  std::uint64_t written_ = 0;
};

}  // namespace wysiwyf
