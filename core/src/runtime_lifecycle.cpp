// A run's lifecycle: select, load, configure, connect (locally, over DDS), activate; hold, deactivate, report.
#include <unistd.h>

#include <cmath>
#include <mutex>

#include "runtime_impl.hpp"
#include "wysiwyf/context.hpp"
#include "wysiwyf/context_access.hpp"

namespace wysiwyf {

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
    const std::string name =
        spec.participant_name(options.process) + (spec.security.enabled() ? "" : "/" + std::to_string(getpid()));
    detail::DdsParticipantOptions participant{spec.domain_id(),
                                              spec.transport(),
                                              spec.dds.profiles_file.value,
                                              spec.dds.participant_profile.value,
                                              name,
                                              std::nullopt,
                                              spec.dds.discovery_servers.value,
                                              options.one_writer_participants};
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
    slot->inputs = detail::ContextAccess::input_queues(ctx);
    slot->inputs_by_port = detail::ContextAccess::input_queues_by_port(ctx);
    if (slot->spec->is_triggered()) {
      slot->doorbell = std::make_unique<detail::Doorbell>();
      any_triggered = true;
      for (const auto& port : slot->spec->trigger.value) {
        auto* queue = detail::ContextAccess::input_queue(ctx, port);
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
      if (options.unconnected_topics.count(name)) continue;
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

}  // namespace wysiwyf
