#pragma once
// One topic inside a process: the local readers' queues, and the links to DDS that carry the
// topic to and from other processes and monitors. Local delivery is synchronous (the sim clock's
// determinism rests on it); DDS delivery is asynchronous.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "wysiwyf/detail/subscriber_queue.hpp"
#include "wysiwyf/message_traits.hpp"
#include "wysiwyf/qos.hpp"

namespace wysiwyf::detail {

// The DDS side of a writer, implemented in core/src/dds_bridge.cpp. The component's thread only
// copies a sample into the channel's outbox; the bridge's publisher thread serialises and sends
// it, so a monitor attaching or detaching does not change how long a tick takes.
class DdsWriterLink {
 public:
  virtual ~DdsWriterLink() = default;
  // Whether a sample written now goes out: a reader is matched, or the topic is transient-local
  // (a late reader still gets the last samples). Unwatched topics cost no copy.
  virtual bool wanted() const = 0;
  // A sample is waiting in the outbox, `waiting` of them in all, room for `capacity`.
  virtual void queued(std::size_t waiting, std::size_t capacity) = 0;
};

class TopicChannelBase {
 public:
  TopicChannelBase(std::string topic, std::string type_name, eprosima::fastdds::dds::TopicDataType* (*make_type)())
      : topic_(std::move(topic)), type_name_(std::move(type_name)), make_type_(make_type) {}
  virtual ~TopicChannelBase() = default;

  const std::string& topic() const { return topic_; }
  const std::string& type_name() const { return type_name_; }
  // The largest serialised sample of the type (its bounds), from its type support.
  std::uint32_t max_serialized_size() const;
  eprosima::fastdds::dds::TopicDataType* make_type() const { return make_type_(); }

  int local_writers() const { return local_writers_; }
  virtual int local_readers() const = 0;
  // Strictest QoS among the local ports on this topic, used for the DDS endpoints.
  const Qos& writer_qos() const { return writer_qos_; }
  const Qos& reader_qos() const { return reader_qos_; }
  // A topic with one writer (some local port says so, or the pipeline: set_one_writer()): DDS
  // exclusive ownership for its endpoints.
  bool one_writer() const { return one_writer_ || writer_qos_.single_writer || reader_qos_.single_writer; }
  void set_one_writer() { one_writer_ = true; }

  // The bridge owns the link and unsets it before it goes (null: local only from then on).
  void set_dds_writer(DdsWriterLink* link) {
    // Room while the publisher thread waits for a core or sends a burst of images (a demo frame
    // is a dozen of them: tens of ms). A reliable topic promises every sample: a second of a
    // 1 kHz stream, since a loaded machine can keep the publisher thread off a core for longer
    // than 64 ms (docs/design/kernel-delivery.md); a best-effort one 64 ms; large samples
    // (images, slots of megabytes) 64 or 8.
    const bool large = max_serialized_size() > 64 * 1024;
    const bool reliable = writer_qos_.reliability == Reliability::kReliable;
    const int slack = reliable ? (large ? 64 : 1024) : (large ? 8 : 64);
    if (link && !dds_writer_) open_outbox(std::max({writer_qos_.depth, outbox_depth_, slack}));
    dds_writer_ = link;
  }
  // Room for this many samples between two drains of the publisher thread, when it is more than
  // the writer's depth (a keyed topic written once per instance in a burst: the diagnostics).
  void reserve_outbox(int depth) { outbox_depth_ = depth; }
  // The publisher thread: the oldest sample waiting for DDS into `sample` (of this channel's
  // type); false when none.
  virtual bool take_outgoing(void* sample) = 0;
  // Samples that never reached DDS: the outbox was full when they came (the publisher thread
  // fell behind by the writer's depth).
  virtual std::uint64_t outgoing_dropped() const = 0;
  // Called from a DDS listener thread with a sample of this channel's type, which it may take
  // the contents of (the caller reuses it only as a buffer for the next take). `origin`: the
  // writing process's name from intern_origin(), or null where it is not known.
  virtual void deliver_from_dds(void* sample, const std::string* origin) = 0;
  // A writing process's name, kept for the run (readers' samples point at it).
  const std::string* intern_origin(const std::string& process) {
    std::lock_guard<std::mutex> lock(origins_mutex_);
    for (const std::string& o : origins_)
      if (o == process) return &o;
    return &origins_.emplace_back(process);
  }
  virtual void* create_sample() const = 0;
  virtual void delete_sample(void* sample) const = 0;

 protected:
  // Several local ports share one DDS endpoint: it gets the deepest history, reliability if any
  // port asks for it, and the shortest deadline.
  static void merge_qos(Qos& into, const Qos& port, bool first) {
    if (first) {
      into = port;
      return;
    }
    if (port.depth > into.depth) into.depth = port.depth;
    if (port.reliability == Reliability::kReliable) into.reliability = Reliability::kReliable;
    if (port.durability == Durability::kTransientLocal) into.durability = Durability::kTransientLocal;
    if (port.deadline_ns > 0 && (into.deadline_ns == 0 || port.deadline_ns < into.deadline_ns))
      into.deadline_ns = port.deadline_ns;
    if (port.single_writer) into.single_writer = true;
  }

  virtual void open_outbox(int depth) = 0;

  std::string topic_;
  std::string type_name_;
  eprosima::fastdds::dds::TopicDataType* (*make_type_)();
  int local_writers_ = 0;
  Qos writer_qos_;
  Qos reader_qos_;
  bool one_writer_ = false;
  DdsWriterLink* dds_writer_ = nullptr;
  int outbox_depth_ = 1;
  std::mutex origins_mutex_;
  std::deque<std::string> origins_;  // (a deque: the strings never move)
};

template <class T>
class TopicChannel final : public TopicChannelBase {
 public:
  explicit TopicChannel(std::string topic)
      : TopicChannelBase(std::move(topic), MessageTraits<T>::type_name(), &MessageTraits<T>::make_type) {}

  SubscriberQueue<T>* add_reader(const Qos& qos) {
    merge_qos(reader_qos_, qos, queues_.empty());
    queues_.push_back(std::make_unique<SubscriberQueue<T>>(qos.depth));
    return queues_.back().get();
  }
  void add_writer(const Qos& qos) {
    merge_qos(writer_qos_, qos, local_writers_ == 0);
    ++local_writers_;
  }
  int local_readers() const override { return static_cast<int>(queues_.size()); }

  void publish(const T& sample) {
    for (auto& q : queues_) q->push(sample);
    if (dds_writer_ && dds_writer_->wanted()) {
      // A copy into a reused slot; DDS sends it from the publisher thread.
      dds_writer_->queued(outbox_->push(sample), outbox_->capacity());
    }
  }
  bool take_outgoing(void* sample) override { return outbox_ && outbox_->take(*static_cast<T*>(sample)); }
  std::uint64_t outgoing_dropped() const override { return outbox_ ? outbox_->dropped() : 0; }

  void deliver_from_dds(void* sample, const std::string* origin) override {
    T& s = *static_cast<T*>(sample);
    if (queues_.empty()) return;
    for (std::size_t i = 0; i + 1 < queues_.size(); ++i) queues_[i]->push(s, origin);
    queues_.back()->push_swap(s, origin);  // the last reader gets the buffer itself: no copy
  }
  void* create_sample() const override { return new T(); }
  void delete_sample(void* sample) const override { delete static_cast<T*>(sample); }

 private:
  void open_outbox(int depth) override { outbox_ = std::make_unique<SubscriberQueue<T>>(depth); }

  std::vector<std::unique_ptr<SubscriberQueue<T>>> queues_;
  std::unique_ptr<SubscriberQueue<T>> outbox_;  // samples on their way to DDS
};

}  // namespace wysiwyf::detail
