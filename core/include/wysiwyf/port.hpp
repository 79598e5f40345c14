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
  Qos qos;  // the component's default; the pipeline may override it
};

// Receives samples of T. Unconnected (describe/validate mode) it never has data.
template <class T>
class Input {
 public:
  Input() = default;
  Input(detail::SubscriberQueue<T>* queue, std::string port) : queue_(queue), port_(std::move(port)) {}

  // Oldest unread sample; false when none arrived since the last read. For streams where every
  // sample counts (setpoints, frames to record).
  bool take(T& out) { return queue_ && queue_->take(out); }
  // Newest unread sample, dropping older unread ones; false when none arrived. For latest-value
  // streams (images, sensor readings) where only the newest matters.
  bool take_latest(T& out) { return queue_ && queue_->take_latest(out); }
  std::size_t pending() const { return queue_ ? queue_->size() : 0; }
  std::uint64_t received() const { return queue_ ? queue_->received() : 0; }
  // Samples pushed out unread by newer ones (the queue's depth was too small for the reader).
  std::uint64_t dropped() const { return queue_ ? queue_->dropped() : 0; }
  bool connected() const { return queue_ != nullptr; }
  const std::string& port() const { return port_; }
  // The process that wrote the sample the last take returned, as it names itself on DDS
  // ("<pipeline>/<group>/<pid>": a fault can name a lost process group); empty for a sample
  // from this process (or from a writer not yet discovered).
  const std::string& writer() const {
    static const std::string kThisProcess;
    const std::string* origin = queue_ ? queue_->taken_origin() : nullptr;
    return origin ? *origin : kThisProcess;
  }

 private:
  detail::SubscriberQueue<T>* queue_ = nullptr;
  std::string port_;
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
