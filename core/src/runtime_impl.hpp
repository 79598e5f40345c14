#pragma once
// The executor's state, Runtime::Impl, and which file holds each of its parts.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <vector>

#include <fastdds/dds/topic/TopicDataType.hpp>

#include "dds_bridge.hpp"
#include "runtime_slot.hpp"
#include "wysiwyf/kernel_msgs.hpp"
#include "wysiwyf/runtime.hpp"

namespace wysiwyf {

using Clock = std::chrono::steady_clock;

struct Runtime::Impl final : detail::RunHost {
  using Slot = detail::Slot;

  Impl(PipelineSpec s, Loader& l, RunOptions o) : spec(std::move(s)), loader(l), options(std::move(o)) {}

  const PipelineSpec spec;
  Loader& loader;
  RunOptions options;
  // Destroyed in reverse: slots (components) first, then the DDS bridge, then the topics.
  detail::TopicBus bus;
  std::unique_ptr<detail::DdsBridge> bridge;
  std::vector<std::unique_ptr<Slot>> slots;
  Output<kernel_msgs::Diagnostics> diagnostics;
  kernel_msgs::Diagnostics diag_msg;

  std::mutex stop_mutex;
  std::condition_variable stop_cv;
  std::atomic<bool> stopping{false};
  std::string stop_reason;
  std::string fault;  // first failure: who, where, what
  std::mutex log_mutex;

  std::ostream& log_stream() { return options.log ? *options.log : std::cerr; }

  // Stops, log lines, faults and one tick (runtime.cpp).
  void request_stop(const std::string& component, const std::string& reason) override;
  void log(const std::string& component, const std::string& message) override;
  void fail(Slot& slot, const std::string& phase, const std::string& what);

  // Calls fn on the slot's component, turning an exception into a reported fault. `phase` (a
  // string, or a callable that makes one) names what was called; it is made only on failure.
  template <class Phase, class Fn>
  bool guarded(Slot& slot, const Phase& phase, Fn&& fn) {
    const auto phase_text = [&]() -> std::string {
      if constexpr (std::is_invocable_v<Phase>)
        return phase();
      else
        return phase;
    };
    try {
      fn();
      return true;
    } catch (const std::exception& e) {
      fail(slot, phase_text(), e.what());
    } catch (...) {
      fail(slot, phase_text(), "an exception that is not a std::exception");
    }
    return false;
  }

  // late_us: how long after its deadline the tick started (real clock).
  void tick(Slot& slot, Time now, double late_us = 0);
  bool flush_after_tick = false;  // real clock: each tick wakes the publisher; sim clock: each step

  // The sim clock (runtime_sim_clock.cpp).
  // Sim clock: the data-triggered components whose inputs got samples tick now, in file order,
  // pass after pass until none is rung (a chain runs as one wave in the producer's step).
  void serve_triggered(std::int64_t t);
  // Sim clock, at the end of a step: a data-triggered component with a trigger_timeout that has
  // not ticked for that long ticks now (and what it writes is served in this step).
  void serve_trigger_timeouts(std::int64_t t);
  static constexpr int kMaxTriggerPasses = 1000;

  // The feed's samples: deserialised with the topic's type into a sample kept per topic, then
  // delivered like a DDS sample.
  struct FeedTarget {
    detail::TopicChannelBase* channel = nullptr;
    std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type;
    void* sample = nullptr;
    ~FeedTarget() {
      if (channel && sample) channel->delete_sample(sample);
    }
  };
  std::map<std::string, FeedTarget> feed_targets;
  eprosima::fastrtps::rtps::SerializedPayload_t feed_payload;
  RunResult* feed_result = nullptr;
  SampleFeed::Deliver feed_deliver = [this](const std::string& topic, const std::uint8_t* cdr, std::size_t size) {
    deliver_fed(topic, cdr, size);
  };
  void deliver_fed(const std::string& topic, const std::uint8_t* cdr, std::size_t size);
  bool any_triggered = false;

  // Diagnostics on wysiwyf/diagnostics (runtime_diagnostics.cpp).
  void publish_diagnostics(Time now, double window_s, bool final);

  // The real clock (runtime_real_clock.cpp).
  // SCHED_FIFO for the slot's thread; without the right (CAP_SYS_NICE or an rtprio limit) it
  // says so and runs at normal priority.
  void set_fifo_priority(Slot& slot);

  // Pins the slot's thread to its `cpus`; a CPU this machine lacks, or a refusal, is said and the
  // thread runs where the process may.
  void set_cpus(Slot& slot);

  // Setup and teardown (runtime_lifecycle.cpp); the clocks' loops (runtime_sim_clock.cpp, runtime_real_clock.cpp).
  bool setup(RunResult& result);
  void run_sim(RunResult& result);
  void run_real(RunResult& result);
  void teardown(RunResult& result);
  void progress(std::int64_t t, std::int64_t duration, Clock::time_point start, bool last);
};

}  // namespace wysiwyf
