// The sim clock: lockstep steps in file order, data-triggered ticks within a step, a feed's samples, progress.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <thread>

#include "runtime_impl.hpp"

namespace wysiwyf {

void Runtime::Impl::serve_triggered(std::int64_t t) {
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

void Runtime::Impl::serve_trigger_timeouts(std::int64_t t) {
  for (auto& slot : slots) {
    if (!fault.empty()) return;
    if (!slot->trigger_timeout_ns || t - std::max<std::int64_t>(slot->last_tick_ns, 0) < slot->trigger_timeout_ns)
      continue;
    tick(*slot, Time{t});
    serve_triggered(t);
  }
}

void Runtime::Impl::deliver_fed(const std::string& topic, const std::uint8_t* cdr, std::size_t size) {
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

}  // namespace wysiwyf
