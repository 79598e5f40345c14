// Checks a parsed pipeline against the component libraries: runs each component's configure()
// in validate mode (parameters read and checked, nothing connected), then checks names, topics
// and types across the whole pipeline.
#include <algorithm>
#include <filesystem>
#include <iterator>
#include <map>
#include <set>

#include "wysiwyf/dds_security.hpp"
#include "wysiwyf/kernel_msgs.hpp"
#include "wysiwyf/validator.hpp"
#include "wysiwyf/context_access.hpp"

namespace wysiwyf {

ComponentDescription describe_component(Loader& loader, const std::string& type) {
  const ComponentLibrary& lib = loader.load(type);
  ComponentPtr component = loader.create(type);
  Context ctx(Context::Mode::kDescribe, nullptr, nullptr);
  component->configure(ctx);
  return ComponentDescription{type, detail::ContextAccess::summary_text(ctx), lib.path,
                              detail::ContextAccess::declared_params(ctx), detail::ContextAccess::declared_ports(ctx)};
}

namespace {

std::string join(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string near = closest_name(word, candidates);
  return near.empty() ? "" : " (did you mean '" + near + "'?)";
}

struct PortUse {
  std::string label;  // "instance.port"
  std::string type;
  PortDirection direction;
  Location where;
  bool single_writer = false;
  Reliability reliability = Reliability::kReliable;
  Durability durability = Durability::kVolatile;
  std::int64_t deadline_ns = 0;    // 0: none
  bool unmapped_optional = false;  // an optional input the pipeline did not connect to a topic
  std::string process;             // its component's process group
};

// Between process groups a topic is a DDS writer and reader, which DDS matches only when the
// writer offers what the reader asks: reliability and durability at least as strong, a deadline
// at least as short. (Inside one
// process the kernel hands samples over whatever they ask.)
template <class Error>
void check_across_processes(const std::string& topic, const std::vector<PortUse>& uses, Error& error) {
  for (const auto& in : uses) {
    if (in.direction != PortDirection::kInput) continue;
    for (const auto& out : uses) {
      if (out.direction != PortDirection::kOutput || out.process == in.process) continue;
      std::string policy;
      if (in.reliability == Reliability::kReliable && out.reliability == Reliability::kBestEffort)
        policy = "wants reliable samples, but " + out.label + " (process '" + out.process +
                 "') offers best effort (RELIABILITY); expected a best-effort input (Qos::sensor)";
      else if (in.durability == Durability::kTransientLocal && out.durability == Durability::kVolatile)
        policy = "wants the last samples kept for late readers, but " + out.label + " (process '" + out.process +
                 "') keeps none (DURABILITY); expected a volatile input";
      else if (in.deadline_ns > 0 && (out.deadline_ns == 0 || out.deadline_ns > in.deadline_ns))
        policy = "wants a sample at least every " + std::to_string(in.deadline_ns / 1'000'000) + " ms, but " +
                 out.label + " (process '" + out.process + "') offers " +
                 (out.deadline_ns ? std::to_string(out.deadline_ns / 1'000'000) + " ms" : std::string("no deadline")) +
                 " (DEADLINE); expected the writer's qos deadline at most the reader's";
      if (!policy.empty())
        error(in.where, "topic '" + topic + "': port " + in.label + " (process '" + in.process + "') " + policy +
                            ", or both in one process group: across processes DDS refuses this reader");
    }
  }
}

// A one-writer input (the arm's setpoint) that takes its writer from another process group, or
// from a program outside the pipeline (no component of it writes the topic), without
// DDS-Security trusts a name or a stream that any participant on the domain can claim: refused
// unless the pipeline says `insecure: true`, and then every start says so for the outside one
// (the process groups' warning says it for the other).
// `writer`: the topic's first writer in the pipeline, null when none.
template <class Error, class Warn>
void check_remote_one_writer(const PipelineSpec& spec, const std::string& topic, const PortUse* writer,
                             const PortUse& input, Error& error, Warn& warn) {
  if (spec.security.enabled() || (writer && writer->process == input.process)) return;
  if (spec.accepts_insecure()) {
    if (!writer)
      warn(input.where, "INSECURE (insecure: true): topic '" + topic + "': " + input.label +
                            " takes its one writer from a program outside this pipeline, unauthenticated: any "
                            "participant on domain " +
                            std::to_string(spec.domain_id()) + " can be that writer");
    return;
  }
  const std::string from = writer
                               ? writer->label + " in process group '" + writer->process + "'"
                               : std::string("a program outside this pipeline (no component of it writes the topic)");
  error(input.where, "topic '" + topic + "': " + input.label + " (process group '" + input.process +
                         "') takes its one writer from " + from +
                         ", over DDS without security, where any participant on the domain can " +
                         (writer ? "claim that name" : "be that writer") +
                         "; expected `security:` (docs/deployment.md), or `insecure: true` at the top of the "
                         "pipeline to accept it knowingly");
}

}  // namespace

ValidationResult validate_pipeline(const PipelineSpec& spec, Loader& loader, const std::string& process) {
  ValidationResult result;
  auto error = [&](const Location& where, std::string msg) { result.errors.push_back({where, std::move(msg)}); };

  if (!process.empty()) {
    const auto groups = spec.processes();
    if (std::find(groups.begin(), groups.end(), process) == groups.end())
      error(Location{spec.file, 0, 0}, "process '" + process + "' is not in the pipeline; expected one of " +
                                           join(groups) + did_you_mean(process, groups));
  }

  if (!spec.security.enabled() && spec.processes().size() > 1) {
    const std::string trusted =
        "every participant on domain " + std::to_string(spec.domain_id()) + " is trusted and its samples are read";
    result.warnings.push_back(
        {Location{spec.file, 0, 0},
         std::string(spec.accepts_insecure() ? "INSECURE (insecure: true): " : "") + "the process groups (" +
             join(spec.processes()) + ") talk over DDS without security: " + trusted +
             ". A one-writer topic (the arm's setpoint) is taken only from the group that writes it here, by a "
             "name that is not authenticated; across machines, turn on `security:` (docs/deployment.md)"});
  }

  if (spec.security.enabled()) {
    // The process this validation is for authenticates as its group's identity.
    const std::string label = spec.process_label(process);
    const auto it = spec.security.identities.find(label);
    if (it == spec.security.identities.end()) {
      std::vector<std::string> named;
      for (const auto& [group, identity] : spec.security.identities) named.push_back(group);
      error(spec.security.where, "security: process '" + label + "' has no identity; expected `" + label +
                                     ": <identity>` under security.identities (it names " +
                                     (named.empty() ? "none" : join(named)) +
                                     (label == "all" ? "; `all` is every process group run in one process" : "") + ")");
    } else {
      for (const auto& f : dds::security_files({spec.security.keys.value, it->second.value}))
        if (!std::filesystem::exists(f)) {
          error(it->second.where, "security identity '" + it->second.value + "' of process '" + label + "': missing " +
                                      f + "; expected the files scripts/security makes");
          break;
        }
    }
  }

  std::map<std::string, std::vector<PortUse>> topics;
  for (const auto& c : spec.components) {
    if (!c.is_enabled() || !c.type.set) continue;
    const std::string label = "component '" + c.name + "' (" + c.type.value + ")";
    ComponentPtr component;
    try {
      component = loader.create(c.type.value);
    } catch (const LoadError& e) {
      error(c.type.where, e.what());
      continue;
    }
    Context ctx(Context::Mode::kValidate, &c, nullptr);
    component->attach(nullptr, c.name);
    try {
      component->configure(ctx);
    } catch (const std::exception& e) {
      error(c.where, label + " rejected its configuration: " + e.what());
      continue;
    }
    for (const auto& issue : ctx.issues()) result.errors.push_back(issue);

    std::vector<std::string> param_names;
    for (const auto& p : detail::ContextAccess::declared_params(ctx)) param_names.push_back(p.name);
    for (const auto& [name, value] : c.params)
      if (std::find(param_names.begin(), param_names.end(), name) == param_names.end())
        error(c.param_keys.at(name), "unknown parameter '" + name + "' for " + label + "; expected one of " +
                                         (param_names.empty() ? "(it has no parameters)" : join(param_names)) +
                                         did_you_mean(name, param_names));

    std::vector<std::string> port_names;
    for (const auto& p : detail::ContextAccess::declared_ports(ctx)) port_names.push_back(p.name);
    for (const auto& [port, topic] : c.topics)
      if (std::find(port_names.begin(), port_names.end(), port) == port_names.end())
        error(c.topic_keys.at(port), "unknown port '" + port + "' for " + label + "; expected one of " +
                                         (port_names.empty() ? "(it has no ports)" : join(port_names)) +
                                         did_you_mean(port, port_names));
    if (c.is_triggered()) {
      std::vector<std::string> inputs;
      for (const auto& p : detail::ContextAccess::declared_ports(ctx))
        if (p.direction == PortDirection::kInput) inputs.push_back(p.name);
      for (const auto& port : c.trigger.value)
        if (std::find(inputs.begin(), inputs.end(), port) == inputs.end())
          error(c.trigger.where,
                "trigger '" + port + "' of " + label + " is not one of its input ports; expected one of " +
                    (inputs.empty() ? "(it has no inputs)" : join(inputs)) + did_you_mean(port, inputs));
    }
    for (const auto& [port, where] : c.qos_where)
      if (std::find(port_names.begin(), port_names.end(), port) == port_names.end())
        error(where, "qos for unknown port '" + port + "' of " + label + "; expected one of " + join(port_names) +
                         did_you_mean(port, port_names));

    for (const auto& p : detail::ContextAccess::declared_ports(ctx)) {
      auto t = c.topics.find(p.name);
      const Location where = t != c.topics.end() ? t->second.where : c.where;
      const auto over = c.qos.find(p.name);  // the pipeline's qos: for the port, as the kernel applies it
      const Qos q = over == c.qos.end() ? p.qos : over->second.apply(p.qos);
      topics[c.topic_for(p.name)].push_back(PortUse{c.name + "." + p.name, p.type_name, p.direction, where,
                                                    q.single_writer, q.reliability, q.durability, q.deadline_ns,
                                                    q.optional && t == c.topics.end(), c.process_name()});
    }
    result.described[c.name] =
        ComponentDescription{c.type.value, detail::ContextAccess::summary_text(ctx), loader.load(c.type.value).path,
                             detail::ContextAccess::declared_params(ctx), detail::ContextAccess::declared_ports(ctx)};
  }

  for (const auto& [topic, uses] : topics) {
    const PortUse& first = uses.front();
    for (const auto& use : uses)
      if (use.type != first.type)
        error(use.where, "topic '" + topic + "': port " + use.label + " carries " + use.type + " but port " +
                             first.label + " (" + first.where.str() + ") carries " + first.type +
                             "; expected one message type per topic");
    const auto writer =  // (the first; a one-writer topic's others are errors below)
        std::find_if(uses.begin(), uses.end(), [](const PortUse& u) { return u.direction == PortDirection::kOutput; });
    // The kernel itself publishes every component's diagnostics.
    const bool produced = topic == kDiagnosticsTopic || writer != uses.end();
    const bool unconnected =
        !produced && std::all_of(uses.begin(), uses.end(), [](const PortUse& u) { return u.unmapped_optional; });
    if (unconnected) result.unconnected_topics.insert(topic);
    if (!produced)
      for (const auto& use : uses)
        if (!use.unmapped_optional && !use.single_writer)  // (a one-writer input: check_remote_one_writer)
          result.warnings.push_back({use.where, "no component of this pipeline publishes topic '" + topic +
                                                    "' (read by " + use.label +
                                                    "); it must come from another program"});
    check_across_processes(topic, uses, error);
    if (std::any_of(uses.begin(), uses.end(), [](const PortUse& u) { return u.single_writer; })) {
      result.one_writer_topics.insert(topic);
      // Written here: only the writer's process group may own it (the DDS readers refuse others).
      if (writer != uses.end()) result.one_writer_participants[topic] = spec.participant_name(writer->process);
    }
    // An input that takes one writer (a robot's setpoint): every writer after the first is an error.
    const auto one_writer = std::find_if(uses.begin(), uses.end(), [](const PortUse& u) {
      return u.single_writer && u.direction == PortDirection::kInput;
    });
    if (one_writer == uses.end() || unconnected) continue;
    auto warn = [&](const Location& where, std::string msg) { result.warnings.push_back({where, std::move(msg)}); };
    check_remote_one_writer(spec, topic, writer == uses.end() ? nullptr : &*writer, *one_writer, error, warn);
    // Between processes the topic has DDS exclusive ownership, which a writer must declare too.
    for (const auto& use : uses)
      if (use.direction == PortDirection::kOutput && !use.single_writer && use.process != one_writer->process)
        error(use.where, "topic '" + topic + "': port " + use.label + " (process '" + use.process + "') writes it to " +
                             one_writer->label + " (process '" + one_writer->process +
                             "'), which takes one writer only, but does not declare itself that writer: across "
                             "processes DDS would refuse its samples (ownership); expected an output declared with "
                             "Qos::one_writer(), or both in one process group");
    for (auto use = writer == uses.end() ? writer : std::next(writer); use != uses.end(); ++use)
      if (use->direction == PortDirection::kOutput)
        error(use->where, "topic '" + topic + "': port " + use->label + " writes it, but " + writer->label + " (" +
                              writer->where.str() + ") already does, and " + one_writer->label +
                              " takes one writer only; expected a single writer");
  }
  return result;
}

}  // namespace wysiwyf
