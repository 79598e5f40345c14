#pragma once
// Carries a process's topics over Fast DDS: a DataWriter for every topic a local component
// publishes (so other processes and monitors see it), a DataReader for every topic local
// components read but no local component publishes.
//
// Components never call Fast DDS while they tick: a written sample is copied into its channel's
// outbox (when someone outside listens), and the bridge's publisher thread serialises and sends
// it. The executor wakes that thread after the tick (flush_soon), outside the tick's timing,
// unless every reader of the topic declared it takes batches (the monitoring tools, on the real
// clock): then only after the tick that ends each dds::kBatchingPeriod, and the loop pays a
// cross-CPU wake every few ticks instead of after each.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "wysiwyf/dds.hpp"
#include "wysiwyf/dds_security.hpp"
#include "wysiwyf/detail/doorbell.hpp"
#include "wysiwyf/detail/topic_channel.hpp"

namespace wysiwyf::detail {

// What DDS says went wrong on one topic: endpoints of another process whose QoS cannot match
// (both sides report it), samples DDS lost on the way in, samples the outbox dropped on the way out.
struct DdsTopicHealth {
  std::string topic;
  std::uint64_t incompatible_qos = 0;  // matches refused, this side's count
  std::string last_incompatible;       // the last refused policy, e.g. "RELIABILITY"
  std::uint64_t lost = 0;              // reader: samples DDS reports lost (best effort gaps, full history)
  std::uint64_t outbox_dropped = 0;    // writer: samples the publisher thread had no time to send
  std::uint64_t ignored = 0;           // reader of a one-writer topic: samples of a writer not its owner
  std::uint64_t deadline_missed = 0;   // reader: deadline periods without a sample
};

// The process's participant: where, over what, and as whom.
struct DdsParticipantOptions {
  int domain = 0;
  std::string transport = "default";
  std::string profiles_file;        // Fast DDS XML profiles ("" none)
  std::string participant_profile;  // a participant profile in it ("" the transport's QoS)
  std::string name;                 // announced in discovery
  std::optional<dds::SecurityIdentity> security;
  std::vector<std::string> discovery_servers;  // IPv4:port; empty: multicast discovery
  // One-writer topics written by a process group of this pipeline: the participant
  // ("<pipeline>/<group>") whose writers alone may own it. Any other participant's samples are
  // refused, before and after the owner is lost.
  std::map<std::string, std::string> writer_participants;
};

class DdsBridge {
 public:
  // `report` gets one line for each problem DDS reports (QoS mismatch, lost samples, a writer or
  // reader the security permissions refuse), from DDS's threads; it must be thread-safe. Null:
  // they are only counted.
  explicit DdsBridge(const DdsParticipantOptions& options, std::function<void(const std::string&)> report = nullptr);
  ~DdsBridge();
  DdsBridge(const DdsBridge&) = delete;
  DdsBridge& operator=(const DdsBridge&) = delete;

  void connect(TopicChannelBase& channel);
  // Wakes the publisher thread if a sample waits for it. Cheap when none does; a wake costs a
  // futex call, so the executor calls it after a tick has been timed. Without it samples still
  // go out within kIdleFlush.
  void flush_soon() {
    if (dirty_.load(std::memory_order_relaxed) && dirty_.exchange(false, std::memory_order_acq_rel))
      bell_.ring();
    else if (batched_.load(std::memory_order_relaxed))
      flush_batch_if_due();
  }
  // Real clock: a writer whose matched readers all declared a latency budget of
  // dds::kBatchingPeriod or more (monitors) does not wake the publisher after every tick, only
  // after the first tick once a batching period has passed: its samples go out in batches, and
  // still right after a tick, while the loop waits for its next one. Off (the sim clock): every
  // sample wakes it.
  void send_in_batches(bool on) { batching_.store(on, std::memory_order_relaxed); }
  std::vector<DdsTopicHealth> health() const;
  // Sends what still waits and stops the publisher thread (the destructor does it too).
  void stop_publishing();
  // Samples sent to other processes, and the publisher thread's wakes that sent any.
  std::uint64_t samples_sent() const { return samples_sent_.load(std::memory_order_relaxed); }
  std::uint64_t wakes_that_sent() const { return wakes_that_sent_.load(std::memory_order_relaxed); }

  // What waits is sent at the latest this long after the last wake (samples written outside a tick).
  static constexpr std::chrono::milliseconds kIdleFlush = 2 * dds::kBatchingPeriod;

 private:
  struct WriterLink;
  struct ReaderLink;
  struct ParticipantNames;
  struct Counters;  // what DDS reports for one endpoint (dds_bridge_listeners.hpp)
  // "'<participant name>' (writer <GUID>)", or the GUID alone before its participant is known.
  std::string writer_name(const eprosima::fastdds::dds::InstanceHandle_t& writer) const;
  // The name of the writer's participant ("<pipeline>/<group>/<pid>"), empty while not discovered.
  std::string process_name(const eprosima::fastdds::dds::InstanceHandle_t& writer) const;
  // Whether a matched reader declared it takes samples in batches (ParticipantNames saw it).
  bool takes_batches(const eprosima::fastdds::dds::InstanceHandle_t& reader) const;
  void publish_loop();
  // Rings the publisher if the batching period has passed since the last batch (one caller wins).
  void flush_batch_if_due();
  // Why DDS may have refused an endpoint: "" without security.
  std::string refused_by_permissions(const std::string& action) const;
  void say(const std::string& line) const {
    if (report_) report_(line);
  }

  std::map<std::string, std::string> writer_participants_;  // DdsParticipantOptions::writer_participants
  std::unique_ptr<ParticipantNames> names_;                 // the participant's listener: outlives it
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::function<void(const std::string&)> report_;
  std::string identity_;              // the DDS-Security identity, "" without
  bool data_sharing_;                 // dds::uses_data_sharing of the transport
  mutable std::mutex writers_mutex_;  // connect() adds while the publisher thread sends
  std::vector<std::unique_ptr<WriterLink>> writers_;
  std::vector<std::unique_ptr<ReaderLink>> readers_;
  std::atomic<bool> dirty_{false};              // some writer's outbox has samples and wants a wake
  std::atomic<bool> batching_{false};           // send_in_batches
  std::atomic<bool> batched_{false};            // some writer's outbox has samples for readers that take batches
  std::atomic<std::int64_t> next_batch_ns_{0};  // steady clock: when the next batch is due
  std::atomic<std::uint64_t> samples_sent_{0}, wakes_that_sent_{0};
  Doorbell bell_;
  std::thread publisher_thread_;
};

}  // namespace wysiwyf::detail
