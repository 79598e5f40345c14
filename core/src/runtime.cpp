// The executor: lifecycle, the sim (lockstep) and real (one periodic thread per component)
// clocks, data-triggered ticks on both, diagnostics, and clean stops on faults and signals.
#include "wysiwyf/runtime.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <mutex>
#include <set>
#include <type_traits>
#include <thread>

#include <fastdds/dds/topic/TopicDataType.hpp>

#include "dds_bridge.hpp"
#include "wysiwyf/detail/doorbell.hpp"
#include "tick_cost.hpp"
#include "tick_stats.hpp"
#include "wysiwyf/kernel_msgs.hpp"
#include "wysiwyf/real_time_throttling.hpp"
#include "wysiwyf/tick_deadline.hpp"

namespace wysiwyf {

using Clock = std::chrono::steady_clock;
using kernel_msgs::ComponentState;

namespace {

std::int64_t wall_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Where a component's requests end up: the executor.
class RunHost {
 public:
  virtual ~RunHost() = default;
  virtual void request_stop(const std::string& component, const std::string& reason) = 0;
  virtual void log(const std::string& component, const std::string& message) = 0;
};

// One component of the run, and the kernel's view of it: its own ComponentHost, so what it
// reports (warnings, rejected samples) is counted where its diagnostics are made.
struct Slot final : ComponentHost {
  const ComponentSpec* spec = nullptr;
  RunHost* run = nullptr;
  ComponentPtr component;
  std::int64_t period_ns = 0;
  enum class Stage { kCreated, kConfigured, kActive, kDeactivated } stage = Stage::kCreated;
  detail::TickStats stats;
  std::string last_error;
  std::uint64_t diag_seq = 0;
  std::vector<const detail::QueueCounters*> inputs;
  std::map<std::string, detail::QueueCounters*> inputs_by_port;
  std::unique_ptr<detail::Doorbell> doorbell;  // data-triggered: rung by its trigger inputs
  std::int64_t trigger_timeout_ns = 0;         // data-triggered: tick anyway after this much silence (0: never)
  std::int64_t last_tick_ns = -1;              // sim clock: when it last ticked
  // What the component reported (from its tick thread: under health_mutex).
  std::mutex health_mutex;
  std::set<std::string> warned;
  std::uint64_t warnings = 0, rejected = 0;
  std::string last_warning;
  Health health = Health::kOk;  // as reported now, and the worst of the run with its first reason
  std::string health_reason;
  Health worst_health = Health::kOk;
  std::string worst_reason;

  std::string label() const { return "component '" + spec->name + "' (" + spec->type.value + ")"; }
  std::uint64_t dropped() const {
    std::uint64_t n = 0;
    for (const auto* q : inputs) n += q->dropped();
    return n;
  }

  void request_stop(const std::string& reason) override { run->request_stop(spec->name, reason); }
  void log(const std::string& message) override { run->log(spec->name, message); }
  void warn_once(const std::string& key, const std::string& message) override {
    bool first = false;
    {
      std::lock_guard<std::mutex> lock(health_mutex);
      ++warnings;
      first = warned.insert(key).second;
      if (first) last_warning = message;
    }
    if (first) run->log(spec->name, "warning: " + message);
  }
  void reject_sample(const std::string& port, const std::string& why) override {
    {
      std::lock_guard<std::mutex> lock(health_mutex);
      ++rejected;
    }
    // Once per port and kind of reason (its text up to the first ':'): "stale: stamped 61.2 ms
    // ago" and "stale: stamped 61.3 ms ago" are one warning, not one per sample.
    warn_once("reject " + port + ": " + why.substr(0, why.find(':')),
              "input '" + port + "': rejected a sample: " + why + " (further ones are counted in the diagnostics)");
  }
  void report_health(Health h, const std::string& reason) override {
    {
      std::lock_guard<std::mutex> lock(health_mutex);
      health = h;
      health_reason = reason;
      if (static_cast<int>(h) > static_cast<int>(worst_health)) {
        worst_health = h;
        worst_reason = reason;
      }
    }
    run->log(spec->name, std::string(to_string(h)) + (reason.empty() ? "" : ": " + reason));
  }
};

}  // namespace

struct Runtime::Impl final : RunHost {
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

  void request_stop(const std::string& component, const std::string& reason) override {
    std::lock_guard<std::mutex> lock(stop_mutex);
    if (!stopping.load()) stop_reason = component.empty() ? reason : "stopped by " + component + ": " + reason;
    stopping.store(true);
    stop_cv.notify_all();
    for (auto& slot : slots)
      if (slot->doorbell) slot->doorbell->stop();
  }
  void log(const std::string& component, const std::string& message) override {
    std::lock_guard<std::mutex> lock(log_mutex);
    log_stream() << "[" << component << "] " << message << "\n";
  }
  void fail(Slot& slot, const std::string& phase, const std::string& what) {
    {
      std::lock_guard<std::mutex> lock(stop_mutex);
      slot.last_error = what;
      if (fault.empty()) fault = slot.label() + " failed in " + phase + ": " + what;
    }
    request_stop("", "fault");
  }

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
  void tick(Slot& slot, Time now, double late_us = 0) {
    slot.last_tick_ns = now.ns;
    const auto t0 = Clock::now();
    const detail::TickCost c0 = options.measure_tick_cost ? detail::thread_cost_now() : detail::TickCost{};
    guarded(
        slot, [now] { return "tick at t=" + std::to_string(now.ns) + " ns"; }, [&] { slot.component->tick(now); });
    const detail::TickCost cost =
        options.measure_tick_cost ? detail::thread_cost_now() - c0 : detail::TickCost{-1, -1};  // (-1: not measured)
    slot.stats.record(std::chrono::duration<double, std::micro>(Clock::now() - t0).count(), late_us, cost.cpu_us,
                      cost.instructions);
    if (flush_after_tick) bridge->flush_soon();  // DDS sends what the tick wrote, on its own thread
  }
  bool flush_after_tick = false;  // real clock: each tick wakes the publisher; sim clock: each step

  // Sim clock: the data-triggered components whose inputs got samples tick now, in file order,
  // pass after pass until none is rung (a chain runs as one wave in the producer's step).
  void serve_triggered(std::int64_t t) {
    if (!any_triggered) return;
    for (int pass = 0;; ++pass) {
      bool ticked = false;
      for (auto& slot : slots) {
        if (!slot->doorbell || !slot->doorbell->take()) continue;
        if (pass >= kMaxTriggerPasses) {
          fail(*slot, "tick at t=" + std::to_string(t) + " ns",
               "its trigger inputs still got samples after " + std::to_string(kMaxTriggerPasses) +
                   " passes in one step; expected data-triggered components without a loop among their triggers");
          return;
        }
        tick(*slot, Time{t});
        ticked = true;
        if (!fault.empty()) return;
      }
      if (!ticked) return;
    }
  }
  // Sim clock, at the end of a step: a data-triggered component with a trigger_timeout that has
  // not ticked for that long ticks now (and what it writes is served in this step).
  void serve_trigger_timeouts(std::int64_t t) {
    for (auto& slot : slots) {
      if (!fault.empty()) return;
      if (!slot->trigger_timeout_ns || t - std::max<std::int64_t>(slot->last_tick_ns, 0) < slot->trigger_timeout_ns)
        continue;
      tick(*slot, Time{t});
      serve_triggered(t);
    }
  }
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
    auto refuse = [&](const std::string& why) { feed_result->feed_refused.emplace(topic, why); };
    auto [it, added] = feed_targets.try_emplace(topic);
    FeedTarget& target = it->second;
    if (added) {
      const auto& channels = bus.channels();
      const auto c = channels.find(topic);
      if (c == channels.end() || c->second->local_readers() == 0) return refuse("no component of the run reads it");
      if (c->second->local_writers() > 0) return refuse("a component of the run publishes it");
      target.channel = c->second.get();
      target.type.reset(target.channel->make_type());
      target.sample = target.channel->create_sample();
    }
    if (!target.sample) return;
    if (feed_payload.max_size < size) feed_payload.reserve(static_cast<std::uint32_t>(size));
    std::memcpy(feed_payload.data, cdr, size);
    feed_payload.length = static_cast<std::uint32_t>(size);
    feed_payload.pos = 0;
    if (!target.type->deserialize(&feed_payload, target.sample))
      return refuse("a sample does not deserialise as " + target.channel->type_name());
    target.channel->deliver_from_dds(target.sample, nullptr);
    ++feed_result->fed_samples;
  };
  bool any_triggered = false;

  void publish_diagnostics(Time now, double window_s, bool final) {
    for (auto& slot : slots) {
      const auto s = slot->stats.summarise();
      auto& d = diag_msg;
      fill_header(d.header(), now.ns, slot->diag_seq++, "");
      d.instance(slot->spec->name);
      d.type(slot->spec->type.value);
      d.process(slot->spec->process_name());
      d.rate_hz(slot->spec->rate.value);
      d.tick_rate_hz(window_s > 0 ? static_cast<double>(s.window_ticks) / window_s : 0.0);
      d.tick_time_p50_us(s.p50_us);
      d.tick_time_p99_us(s.p99_us);
      d.tick_time_max_us(s.max_us);
      d.tick_late_p50_us(s.late_p50_us);
      d.tick_late_p99_us(s.late_p99_us);
      d.tick_late_max_us(s.late_max_us);
      d.ticks(s.ticks);
      d.overruns(s.overruns);
      d.dropped_samples(slot->dropped());
      d.dropped_by_port().clear();
      for (const auto& [port, queue] : slot->inputs_by_port)
        if (queue->dropped() > 0 && d.dropped_by_port().size() < 32) {
          kernel_msgs::PortCount c;
          c.port(port.substr(0, 63));
          c.count(queue->dropped());
          d.dropped_by_port().push_back(c);
        }
      {  // what the component reported, read at once (not held while writing: its thread may report)
        std::lock_guard<std::mutex> lock(slot->health_mutex);
        d.state(!slot->last_error.empty() || slot->health == Health::kFault ? ComponentState::STATE_FAULT
                : slot->health == Health::kHolding                          ? ComponentState::STATE_HOLDING
                : final                                                     ? ComponentState::STATE_STOPPED
                : slot->stage == Slot::Stage::kActive                       ? ComponentState::STATE_ACTIVE
                                                                            : ComponentState::STATE_CONFIGURED);
        d.rejected_samples(slot->rejected);
        d.warnings(slot->warnings);
        d.last_warning(slot->last_warning.substr(0, 255));
        d.last_error((slot->last_error.empty() ? slot->health_reason : slot->last_error).substr(0, 255));
      }
      diagnostics.write(d);
    }
  }

  // SCHED_FIFO for the slot's thread; without the right (CAP_SYS_NICE or an rtprio limit) it
  // says so and runs at normal priority.
  void set_fifo_priority(Slot& slot) {
    sched_param p{};
    p.sched_priority = slot.spec->priority.value;
    if (const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p); err != 0) {
      log(slot.spec->name, "priority " + std::to_string(p.sched_priority) +
                               " (SCHED_FIFO) refused: " + std::strerror(err) +
                               "; expected CAP_SYS_NICE or an rtprio limit (ulimit -r); running at normal priority");
      return;
    }
    // (a periodic thread's spin; a data-triggered one sleeps on its doorbell)
    const std::int64_t spin = !slot.doorbell && slot.spec->spin_ns.set ? slot.spec->spin_ns.value : 0;
    if (const std::string w = real_time_throttling_warning(spin, slot.period_ns, read_real_time_bandwidth());
        !w.empty())
      log(slot.spec->name, "priority " + std::to_string(p.sched_priority) + ": " + w);
  }

  // Pins the slot's thread to its `cpus`; a CPU this machine lacks, or a refusal, is said and the
  // thread runs where the process may.
  void set_cpus(Slot& slot) {
    cpu_set_t set;
    CPU_ZERO(&set);
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    std::string list;
    for (int cpu : slot.spec->cpus.value) {
      list += (list.empty() ? "" : ", ") + std::to_string(cpu);
      if (cpu >= online) {
        log(slot.spec->name, "cpus: CPU " + std::to_string(cpu) + " does not exist (this machine has " +
                                 std::to_string(online) + ", 0 to " + std::to_string(online - 1) +
                                 "); the thread is not pinned");
        return;
      }
      CPU_SET(cpu, &set);
    }
    if (const int err = pthread_setaffinity_np(pthread_self(), sizeof(set), &set); err != 0)
      log(slot.spec->name, "cpus [" + list + "] refused: " + std::strerror(err) + "; the thread is not pinned");
  }

  bool setup(RunResult& result);
  void run_sim(RunResult& result);
  void run_real(RunResult& result);
  void teardown(RunResult& result);
  void progress(std::int64_t t, std::int64_t duration, Clock::time_point start, bool last);
};

bool Runtime::Impl::setup(RunResult& result) {
  for (const auto& c : spec.components) {
    if (!c.is_enabled() || (!options.process.empty() && c.process_name() != options.process)) continue;
    auto slot = std::make_unique<Slot>();
    slot->spec = &c;
    slot->run = this;
    slot->period_ns = static_cast<std::int64_t>(std::llround(1e9 / c.rate.value));
    slots.push_back(std::move(slot));
  }
  if (slots.empty()) {
    result.ok = false;
    result.error = options.process.empty() ? "the pipeline has no enabled components"
                                           : "process '" + options.process + "' has no enabled components";
    return false;
  }
  try {
    // (Announced in clear even with security: the process id only on a plain domain.)
    const std::string name = (spec.name.set ? spec.name.value : "pipeline") + "/" +
                             (options.process.empty() ? "all" : options.process) +
                             (spec.security.enabled() ? "" : "/" + std::to_string(getpid()));
    detail::DdsParticipantOptions participant{spec.domain_id(),
                                              spec.transport(),
                                              spec.dds.profiles_file.value,
                                              spec.dds.participant_profile.value,
                                              name,
                                              std::nullopt,
                                              spec.dds.discovery_servers.value};
    if (spec.security.enabled())  // (validation made sure the process has an identity)
      participant.security = dds::SecurityIdentity{
          spec.security.keys.value, spec.security.identities.at(spec.process_label(options.process)).value};
    bridge = std::make_unique<detail::DdsBridge>(participant, [this](const std::string& line) { log("dds", line); });
  } catch (const std::exception& e) {
    result.ok = false;
    result.error = std::string("DDS: ") + e.what();
    return false;
  }
  for (auto& slot : slots) {
    try {
      slot->component = loader.create(slot->spec->type.value);
    } catch (const std::exception& e) {
      fail(*slot, "load", e.what());
      return false;
    }
    slot->component->attach(slot.get(), slot->spec->name);
    Context ctx(Context::Mode::kRun, slot->spec, &bus);
    if (!guarded(*slot, "configure", [&] { slot->component->configure(ctx); })) return false;
    if (!ctx.issues().empty()) {
      fail(*slot, "configure", ConfigError(ctx.issues()).what());
      return false;
    }
    slot->inputs = ctx.input_queues();
    slot->inputs_by_port = ctx.input_queues_by_port();
    if (slot->spec->is_triggered()) {
      slot->doorbell = std::make_unique<detail::Doorbell>();
      any_triggered = true;
      for (const auto& port : slot->spec->trigger.value) {
        auto* queue = ctx.input_queue(port);
        if (!queue) {
          fail(*slot, "configure",
               "trigger '" + port + "' (" + slot->spec->trigger.where.str() + ") is not one of its input ports");
          return false;
        }
        queue->set_doorbell(slot->doorbell.get());
      }
      if (slot->spec->trigger_timeout_ns.set) slot->trigger_timeout_ns = slot->spec->trigger_timeout_ns.value;
    }
    slot->stage = Slot::Stage::kConfigured;
  }
  Qos diag_qos = Qos::reliable(1);
  diag_qos.durability = Durability::kTransientLocal;  // a monitor started later sees the latest state
  auto* diag_channel = bus.channel<kernel_msgs::Diagnostics>(kDiagnosticsTopic, "kernel.diagnostics");
  diag_channel->add_writer(diag_qos);
  diag_channel->reserve_outbox(static_cast<int>(slots.size()));  // one sample per component, at once
  diagnostics = Output<kernel_msgs::Diagnostics>(diag_channel);
  try {
    for (const auto& [name, channel] : bus.channels()) {
      if (options.one_writer_topics.count(name)) channel->set_one_writer();
      bridge->connect(*channel);
    }
  } catch (const std::exception& e) {
    result.ok = false;
    result.error = std::string("DDS: ") + e.what();
    return false;
  }
  for (auto& slot : slots) {
    if (!guarded(*slot, "activate", [&] { slot->component->activate(); })) return false;
    slot->stage = Slot::Stage::kActive;
  }
  return true;
}

void Runtime::Impl::progress(std::int64_t t, std::int64_t duration, Clock::time_point start, bool last) {
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  const double rtf = wall > 0 ? static_cast<double>(t) * 1e-9 / wall : 0.0;
  if (duration > 0)
    std::fprintf(stderr, "\rsim %9.3f s / %.3f s  (%5.1f%%)  %8.1fx real time", t * 1e-9, duration * 1e-9,
                 100.0 * static_cast<double>(t) / static_cast<double>(duration), rtf);
  else
    std::fprintf(stderr, "\rsim %9.3f s  %8.1fx real time", t * 1e-9, rtf);
  if (last) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

void Runtime::Impl::run_sim(RunResult& result) {
  feed_result = &result;
  const std::int64_t step = spec.step_ns();
  const std::int64_t duration = spec.duration_ns();
  const double pace = spec.pace();
  const auto start = Clock::now();
  auto next_progress = start;
  std::int64_t t = 0;
  std::int64_t next_diag = 0;
  std::uint64_t steps = 0;
  while (true) {
    if (duration > 0 && t >= duration) {
      request_stop("", "duration reached");
      break;
    }
    if (stop_signal_received()) request_stop("", "signal");
    if (stopping.load(std::memory_order_relaxed)) break;
    if (options.feed) options.feed->due(t, feed_deliver);
    serve_triggered(t);  // samples that came over DDS (or from the feed) since the last step
    for (auto& slot : slots) {
      if (!fault.empty()) break;
      if (slot->doorbell || t % slot->period_ns != 0) continue;
      tick(*slot, Time{t});
      serve_triggered(t);
    }
    serve_trigger_timeouts(t);
    if (t >= next_diag) {
      publish_diagnostics(Time{t}, 1.0, false);
      next_diag += kNanosPerSecond;
    }
    bridge->flush_soon();  // DDS sends what this step wrote, on the bridge's thread
    t += step;
    if (pace > 0) std::this_thread::sleep_until(start + std::chrono::nanoseconds(static_cast<std::int64_t>(t / pace)));
    if (options.progress && (++steps & 0xff) == 0 && Clock::now() >= next_progress) {
      progress(t, duration, start, false);
      next_progress = Clock::now() + std::chrono::milliseconds(250);
    }
  }
  if (options.progress) progress(t, duration, start, true);
  result.sim_time_ns = t;
}

void Runtime::Impl::run_real(RunResult& result) {
  const auto start = Clock::now();
  flush_after_tick = true;
  bridge->send_in_batches(true);  // to monitors: no wake of the publisher after every tick
  std::vector<std::thread> threads;
  for (auto& slot_ptr : slots) {
    Slot* slot = slot_ptr.get();
    threads.emplace_back([this, slot, start] {
      prctl(PR_SET_TIMERSLACK, 1UL);  // by default Linux may wake this thread up to 50 us late
      if (slot->spec->priority.set) set_fifo_priority(*slot);
      if (slot->spec->cpus.set) set_cpus(*slot);
      if (slot->doorbell) {  // data-triggered: one tick per ring; late = from the sample's arrival
        using Wake = detail::Doorbell::Wake;
        const auto timeout = std::chrono::nanoseconds(slot->trigger_timeout_ns);
        Clock::time_point rang;
        auto until = slot->trigger_timeout_ns ? Clock::now() + timeout : Clock::time_point::max();
        for (Wake w; (w = slot->doorbell->wait(rang, until)) != Wake::kStopped && !stopping.load();) {
          // A watchdog tick after a silence is on time; a ring's is late by the wait for the thread.
          const double late_us =
              w == Wake::kRang ? std::chrono::duration<double, std::micro>(Clock::now() - rang).count() : 0.0;
          tick(*slot, Time{wall_now_ns()}, late_us);
          if (slot->trigger_timeout_ns) until = Clock::now() + timeout;
        }
        return;
      }
      const auto period = std::chrono::nanoseconds(slot->period_ns);
      // The kernel wakes a sleeping thread tens of microseconds late (hundreds at times on a
      // virtual machine); with `spin` the thread wakes that much early and busy-waits the rest.
      const auto spin = std::chrono::nanoseconds(slot->spec->spin_ns.set ? slot->spec->spin_ns.value : 0);
      auto next = start;
      while (true) {
        {
          std::unique_lock<std::mutex> lock(stop_mutex);
          // Absolute deadlines on a fixed grid: no drift, whatever each tick costs.
          if (stop_cv.wait_until(lock, next - spin, [this] { return stopping.load(); })) return;
        }
        if (!spin_until(next, stopping)) return;
        const double late_us = std::chrono::duration<double, std::micro>(Clock::now() - next).count();
        tick(*slot, Time{wall_now_ns()}, late_us);
        if (const auto missed = advance_deadline(next, period)) slot->stats.add_overruns(missed);
      }
    });
  }
  const std::int64_t duration = spec.duration_ns();
  auto next_diag = start;
  while (!stopping.load()) {
    if (stop_signal_received()) request_stop("", "signal");
    if (duration > 0 && Clock::now() - start >= std::chrono::nanoseconds(duration))
      request_stop("", "duration reached");
    if (Clock::now() >= next_diag) {
      publish_diagnostics(Time{wall_now_ns()}, 1.0, false);
      bridge->flush_soon();
      next_diag += std::chrono::seconds(1);
    }
    std::unique_lock<std::mutex> lock(stop_mutex);
    stop_cv.wait_for(lock, std::chrono::milliseconds(20), [this] { return stopping.load(); });
  }
  for (auto& th : threads) th.join();
  result.sim_time_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count();
}

void Runtime::Impl::teardown(RunResult& result) {
  if (!fault.empty()) {  // a fault: every component makes its hardware safe before anything else
    for (auto& slot : slots)
      if (slot->stage == Slot::Stage::kActive) slot->component->hold();
  }
  for (auto it = slots.rbegin(); it != slots.rend(); ++it) {
    Slot& slot = **it;
    if (slot.stage != Slot::Stage::kActive) continue;
    guarded(slot, "deactivate", [&] { slot.component->deactivate(); });
    slot.stage = Slot::Stage::kDeactivated;
  }
  if (diagnostics.connected()) publish_diagnostics(Time{result.sim_time_ns}, 0.0, true);
  for (auto& slot : slots) {
    const auto s = slot->stats.summarise();
    std::lock_guard<std::mutex> lock(slot->health_mutex);
    result.components.push_back(ComponentReport{
        slot->spec->name, slot->spec->type.value, s.ticks, s.overruns, s.p50_us, s.p99_us, s.max_us, s.run_p99_us,
        s.run_max_us, s.late_p50_us, s.late_p99_us, s.late_max_us, slot->dropped(), slot->rejected, slot->warnings,
        slot->last_error.empty() ? to_string(slot->worst_health) : "failed",
        slot->last_error.empty() ? slot->worst_reason : slot->last_error});
    ComponentReport& r = result.components.back();
    r.cpu_p50_us = s.cpu_p50_us, r.cpu_p99_us = s.cpu_p99_us;
    r.instructions_p50 = s.instructions_p50, r.instructions_p99 = s.instructions_p99;
  }
  // Components go first (reverse order), then DDS, then the topics they wrote to.
  for (auto it = slots.rbegin(); it != slots.rend(); ++it) (*it)->component.reset();
  feed_targets.clear();
  if (bridge) {
    bridge->stop_publishing();
    result.dds_samples_sent = bridge->samples_sent();
    result.dds_publisher_wakes = bridge->wakes_that_sent();
    for (const auto& h : bridge->health()) {
      std::string line = "topic '" + h.topic + "':";
      if (h.incompatible_qos)
        line += " " + std::to_string(h.incompatible_qos) + " endpoint(s) of other processes refused (" +
                h.last_incompatible + ");";
      if (h.lost) line += " " + std::to_string(h.lost) + " samples lost on the way in;";
      if (h.outbox_dropped) line += " " + std::to_string(h.outbox_dropped) + " samples never sent (publisher behind);";
      if (h.ignored) line += " " + std::to_string(h.ignored) + " samples of a second writer ignored (one writer);";
      if (h.deadline_missed) line += " its deadline missed " + std::to_string(h.deadline_missed) + " time(s);";
      line.pop_back();
      result.dds_problems.push_back(line);
    }
  }
  bridge.reset();
  if (!fault.empty()) {
    result.ok = false;
    result.error = fault;
  }
  result.stop_reason = fault.empty() ? stop_reason : "fault";
}

Runtime::Runtime(PipelineSpec spec, Loader& loader, RunOptions options)
    : impl_(std::make_unique<Impl>(std::move(spec), loader, std::move(options))) {}

Runtime::~Runtime() = default;

void Runtime::request_stop(const std::string& reason) { impl_->request_stop("", reason); }

RunResult Runtime::run() {
  RunResult result;
  const auto wall_start = Clock::now();
  if (impl_->setup(result)) {
    if (impl_->options.start_after_s > 0) {
      std::unique_lock<std::mutex> lock(impl_->stop_mutex);
      impl_->stop_cv.wait_for(lock, std::chrono::duration<double>(impl_->options.start_after_s),
                              [this] { return impl_->stopping.load(); });
    }
    if (impl_->spec.clock_mode() == ClockMode::kSim)
      impl_->run_sim(result);
    else
      impl_->run_real(result);
  }
  impl_->teardown(result);
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - wall_start).count();
  return result;
}

}  // namespace wysiwyf
