#pragma once
/// @file
/// The component contract. A component is a class built into its own shared library and exported
/// with WYSIWYF_COMPONENT; the kernel loads it at run time, checks its ABI version and build id,
/// and drives its lifecycle:
///
/// - `configure(ctx)`: declare parameters and ports, read parameter values (no side effects: it also
///   runs when a pipeline is only validated or described)
/// - `activate()`: acquire resources: devices, threads, files
/// - `tick(now)`: called at the component's rate
/// - `deactivate()`: release resources; called in reverse order on every stop
/// - `hold()`: a fault stopped the pipeline: bring hardware to a safe standstill at once;
///   called on every component before any deactivate()
///
/// An exception thrown from any of these is reported with the component's name and stops the
/// pipeline cleanly.
///
/// Threads. configure, activate, deactivate and hold run on the thread that runs the pipeline,
/// one component after the other. tick() runs
///   - on the sim clock: on that same thread, every component in file order within each step
///     (`now` is the simulated time, from 0), so a component never runs while another does;
///   - on the real clock: on a thread of its own, at absolute deadlines on a fixed grid (`now` is
///     wall-clock time since the epoch); different components tick at the same time.
///
/// A component's own calls are never concurrent with each other. Ports are thread-safe.
///
/// Inside tick(): no blocking (no sleeping, no waiting for I/O or locks held across ticks: a late
/// tick delays everything after it on the sim clock and counts as an overrun on the real one), and
/// no heap allocation in steady state (size buffers once, in activate() or the first tick; the
/// ports reuse theirs). log(), warn_once() and reject() take a lock and format text: they are for
/// events, not for every tick.
#include <cstdint>
#include <string>

#include "wysiwyf/build_info.hpp"
#include "wysiwyf/context.hpp"
#include "wysiwyf/time.hpp"

/// The SDK: the component contract (Component, Context, ports, parameters, QoS, time) and the
/// Harness that runs one component in a unit test.
namespace wysiwyf {

/// A component's own view of its health, as it reports it (report_health): kOk; kHolding: holding
/// its hardware or output still because something is wrong (an input stopped, bad input refused);
/// kFault: latched until something resets it. The kernel puts it in the diagnostics and the run's
/// summary, and `wysiwyf run` exits non-zero when any component held or faulted.
enum class Health {
  kOk,       ///< all is well
  kHolding,  ///< holding its hardware or output still because something is wrong
  kFault     ///< latched until something resets it
};
/// The health's name as the diagnostics and logs spell it: "ok", "holding" or "fault".
inline const char* to_string(Health health) {
  return health == Health::kOk ? "ok" : health == Health::kHolding ? "holding" : "fault";
}

/// What a running component may ask of the kernel; the executor (and the test Harness) gives each
/// component its own.
class ComponentHost {
 public:
  virtual ~ComponentHost() = default;
  /// Ends the pipeline cleanly after the current step, with `reason` as the run's stop reason.
  virtual void request_stop(const std::string& reason) = 0;
  /// A line in the pipeline's log, prefixed with the instance name.
  virtual void log(const std::string& message) = 0;
  /// Logs `message` the first time `key` is warned about; later warnings with the same key are
  /// only counted (in the diagnostics).
  virtual void warn_once(const std::string& key, const std::string& message) = 0;
  /// A sample that arrived on input `port` could not be used (`why`): counted in the diagnostics,
  /// logged once per port and reason.
  virtual void reject_sample(const std::string& port, const std::string& why) = 0;
  /// The component's health changed (Component::report_health calls it on changes only).
  virtual void report_health(Health health, const std::string& reason) = 0;
};

/// The base class of every component: derive from it, implement configure() and tick(), export
/// the class with WYSIWYF_COMPONENT. The kernel owns the instance and calls its lifecycle
/// (see component.hpp); the protected members are how it talks to the kernel.
class Component {
 public:
  Component() = default;
  Component(const Component&) = delete;  ///< one owner: the kernel
  Component& operator=(const Component&) = delete;
  virtual ~Component() = default;

  /// Declares parameters and ports and reads parameter values; no side effects (it also runs
  /// when a pipeline is only validated or described).
  virtual void configure(Context& ctx) = 0;
  /// Acquires resources: devices, threads, files.
  virtual void activate() {}
  /// Called at the component's rate; `now` is sim time from 0 or wall-clock time since the epoch.
  virtual void tick(Time now) = 0;
  /// Releases resources; called in reverse order on every stop.
  virtual void deactivate() {}
  /// A fault stopped the pipeline: brings hardware to a safe standstill at once; called on every
  /// component before any deactivate().
  virtual void hold() noexcept {}

  /// Set by the kernel before configure() (host may be null while validating).
  void attach(ComponentHost* host, std::string instance_name) {
    host_ = host;
    instance_name_ = std::move(instance_name);
  }

 protected:
  /// The instance's name in the pipeline.
  const std::string& instance_name() const { return instance_name_; }
  /// Ends the pipeline cleanly after the current step (e.g. a scripted run is done).
  void request_stop(const std::string& reason) {
    if (host_) host_->request_stop(reason);
  }
  /// A line in the pipeline's log, prefixed with the instance name (takes a lock).
  void log(const std::string& message) {
    if (host_) host_->log(message);
  }
  /// A warning logged once per `key` (the message itself by default) and counted every time.
  void warn_once(const std::string& key, const std::string& message) {
    if (host_) host_->warn_once(key, message);
  }
  /// A warning logged once per distinct message and counted every time.
  void warn_once(const std::string& message) { warn_once(message, message); }
  /// The one way to report an input sample that cannot be used (a wrong encoding, a NaN, a short
  /// buffer): counted in the diagnostics and logged once per port and reason. Skip the sample
  /// after it; hardware holds what it had.
  template <class T>
  void reject(const Input<T>& in, const std::string& why) {
    if (host_) host_->reject_sample(in.port(), why);
  }
  /// Takes the next sample that passes its type's checks (problem(sample), found beside the type:
  /// wysiwyf/msg_checks.hpp for the display's messages), rejecting each that does not with why.
  /// False when the port has nothing more.
  template <class T>
  bool take_checked(Input<T>& in, T& out) {
    while (in.take(out)) {
      const std::string why = problem(out);
      if (why.empty()) return true;
      reject(in, why);
    }
    return false;
  }
  /// The component's health now, with why when not kOk; cheap to call every tick (the kernel
  /// hears of changes only).
  void report_health(Health health, const std::string& reason = "") {
    if (health == health_ && (health == Health::kOk || reason == health_reason_)) return;
    health_ = health;
    health_reason_ = health == Health::kOk ? std::string() : reason;
    if (host_) host_->report_health(health_, health_reason_);
  }

 private:
  ComponentHost* host_ = nullptr;
  std::string instance_name_;
  Health health_ = Health::kOk;
  std::string health_reason_;
};

/// Bumped whenever the Component/Context/port layout changes incompatibly.
constexpr std::uint32_t kAbiVersion = 5;

/// The C entry point's answer. abi_version stays the first field in every version.
struct ComponentEntry {
  std::uint32_t abi_version;    ///< kAbiVersion of the SDK the library was built against
  const char* build_id;         ///< WYSIWYF_BUILD_ID of the SDK the library was built against
  const char* type_name;        ///< the component type, as pipelines name it
  Component* (*create)();       ///< a new instance of the component
  void (*destroy)(Component*);  ///< deletes an instance create() made
};

}  // namespace wysiwyf

/// The name of the C entry point WYSIWYF_COMPONENT defines, which the kernel looks up.
#define WYSIWYF_COMPONENT_ENTRY_SYMBOL "wysiwyf_component_entry"

/// Exports Class as the component type `type_name` (one per shared library).
#define WYSIWYF_COMPONENT(Class, type_name)                                                                      \
  extern "C" __attribute__((visibility("default"))) const ::wysiwyf::ComponentEntry* wysiwyf_component_entry() { \
    static const ::wysiwyf::ComponentEntry entry{::wysiwyf::kAbiVersion, WYSIWYF_BUILD_ID, type_name,            \
                                                 []() -> ::wysiwyf::Component* { return new Class(); },          \
                                                 [](::wysiwyf::Component* c) { delete c; }};                     \
    return &entry;                                                                                               \
  }
