#pragma once
/// @file
/// Typed ports. A component gets them from Context::input / Context::output in configure() and
/// keeps them as members; the pipeline file maps each port to a topic.
#include <cstdint>
#include <string>

#include "wysiwyf/detail/topic_channel.hpp"
#include "wysiwyf/qos.hpp"

namespace wysiwyf {

/// Whether a port receives (Input) or publishes (Output).
enum class PortDirection {
  kInput,  ///< an Input: receives samples
  kOutput  ///< an Output: publishes samples
};

/// A declared port, as `wysiwyf components describe` prints it and the validator checks it.
struct PortSpec {
  std::string name;                                 ///< the port's name, as the pipeline maps it to a topic
  PortDirection direction = PortDirection::kInput;  ///< input or output
  std::string type_name;                            ///< DDS type, e.g. "wysiwyf::msg::JointState"
  std::string description;                          ///< the one-line description the component gave
  Qos qos;                                          ///< the component's default; the pipeline may override it
};

/// Receives samples of T. Unconnected (describe/validate mode) it never has data.
template <class T>
class Input {
 public:
  /// An unconnected input: it never has data.
  Input() = default;
  /// An input reading `queue`, named `port` (Context::input and Harness::watch make them).
  Input(detail::SubscriberQueue<T>* queue, std::string port) : queue_(queue), port_(std::move(port)) {}

  /// Oldest unread sample; false when none arrived since the last read. For streams where every
  /// sample counts (setpoints, frames to record).
  bool take(T& out) { return queue_ && queue_->take(out); }
  /// Newest unread sample, dropping older unread ones; false when none arrived. For latest-value
  /// streams (images, sensor readings) where only the newest matters.
  bool take_latest(T& out) { return queue_ && queue_->take_latest(out); }
  /// Samples waiting to be taken.
  std::size_t pending() const { return queue_ ? queue_->size() : 0; }
  /// Samples received since the start, taken or not.
  std::uint64_t received() const { return queue_ ? queue_->received() : 0; }
  /// Samples pushed out unread by newer ones (the queue's depth was too small for the reader).
  std::uint64_t dropped() const { return queue_ ? queue_->dropped() : 0; }
  /// False in describe and validate mode, where the input never has data.
  bool connected() const { return queue_ != nullptr; }
  /// The port's name.
  const std::string& port() const { return port_; }
  /// The process that wrote the sample the last take returned, as it names itself on DDS
  /// (`<pipeline>/<group>/<pid>`: a fault can name a lost process group); empty for a sample
  /// from this process (or from a writer not yet discovered).
  const std::string& writer() const {
    static const std::string kThisProcess;
    const std::string* origin = queue_ ? queue_->taken_origin() : nullptr;
    return origin ? *origin : kThisProcess;
  }

 private:
  detail::SubscriberQueue<T>* queue_ = nullptr;
  std::string port_;
};

/// Publishes samples of T to every local reader at once and to DDS.
template <class T>
class Output {
 public:
  /// An unconnected output: what it writes goes nowhere (still counted).
  Output() = default;
  /// An output publishing on `channel` (Context::output and Harness::feed make them).
  explicit Output(detail::TopicChannel<T>* channel) : channel_(channel) {}

  /// Publishes `sample` to every local reader at once and to DDS.
  void write(const T& sample) {
    if (channel_) channel_->publish(sample);
    ++written_;
  }
  /// Samples written since the start.
  std::uint64_t written() const { return written_; }
  /// False in describe and validate mode, where what is written goes nowhere.
  bool connected() const { return channel_ != nullptr; }

 private:
  detail::TopicChannel<T>* channel_ = nullptr;
  std::uint64_t written_ = 0;
};

}  // namespace wysiwyf
