// The executor: lifecycle, the sim (lockstep) and real (one periodic thread per component)
// clocks, data-triggered ticks on both, diagnostics, and clean stops on faults and signals.
// Here Runtime, and the stops, faults and ticks all parts use; runtime_impl.hpp names the files of the rest.
#include "wysiwyf/runtime.hpp"

#include <chrono>
#include <mutex>

#include "runtime_impl.hpp"
#include "tick_cost.hpp"

namespace wysiwyf {

void Runtime::Impl::request_stop(const std::string& component, const std::string& reason) {
  std::lock_guard<std::mutex> lock(stop_mutex);
  if (!stopping.load()) stop_reason = component.empty() ? reason : "stopped by " + component + ": " + reason;
  stopping.store(true);
  stop_cv.notify_all();
  for (auto& slot : slots)
    if (slot->doorbell) slot->doorbell->stop();
}

void Runtime::Impl::log(const std::string& component, const std::string& message) {
  std::lock_guard<std::mutex> lock(log_mutex);
  log_stream() << "[" << component << "] " << message << "\n";
}

void Runtime::Impl::fail(Slot& slot, const std::string& phase, const std::string& what) {
  {
    std::lock_guard<std::mutex> lock(stop_mutex);
    slot.last_error = what;
    if (fault.empty()) fault = slot.label() + " failed in " + phase + ": " + what;
  }
  request_stop("", "fault");
}

void Runtime::Impl::tick(Slot& slot, Time now, double late_us) {
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
