#pragma once
// One component of a run (Slot) as the executor keeps it, and where its requests go (RunHost).
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "tick_stats.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/detail/doorbell.hpp"
#include "wysiwyf/detail/subscriber_queue.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"

namespace wysiwyf::detail {

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

}  // namespace wysiwyf::detail
