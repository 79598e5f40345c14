#pragma once
// The component contract. A component is a class built into its own shared library and exported
// with WYSIWYF_COMPONENT; the kernel loads it at run time, checks its ABI version and build id,
// and drives its lifecycle:
//
//   configure(ctx)  declare parameters and ports, read parameter values (no side effects: it also
//                   runs when a pipeline is only validated or described)
//   activate()      acquire resources: devices, threads, files
//   tick(now)       called at the component's rate (sim clock: in file order within each step)
//   deactivate()    release resources; called in reverse order on every stop
//   hold()          a fault stopped the pipeline: bring hardware to a safe standstill at once;
//                   called on every component before any deactivate()
//
// An exception thrown from any of these is reported with the component's name and stops the
// pipeline cleanly.
#include <cstdint>
#include <string>

#include "wysiwyf/build_info.hpp"
#include "wysiwyf/context.hpp"
#include "wysiwyf/time.hpp"

namespace wysiwyf {

// What a running component may ask of the kernel; implemented by the executor.
class ComponentHost {
 public:
  virtual ~ComponentHost() = default;
  virtual void request_stop(const std::string& component, const std::string& reason) = 0;
  virtual void log(const std::string& component, const std::string& message) = 0;
};

class Component {
 public:
  Component() = default;
  Component(const Component&) = delete;  // one owner: the kernel
  Component& operator=(const Component&) = delete;
  virtual ~Component() = default;

  virtual void configure(Context& ctx) = 0;
  virtual void activate() {}
  virtual void tick(Time now) = 0;
  virtual void deactivate() {}
  virtual void hold() noexcept {}

  // Set by the kernel before configure().
  void attach(ComponentHost* host, std::string instance_name) {
    host_ = host;
    instance_name_ = std::move(instance_name);
  }

 protected:
  const std::string& instance_name() const { return instance_name_; }
  // Ends the pipeline cleanly after the current step (e.g. a scripted run is done).
  void request_stop(const std::string& reason) {
    if (host_) host_->request_stop(instance_name_, reason);
  }
  void log(const std::string& message) {
    if (host_) host_->log(instance_name_, message);
  }

 private:
  ComponentHost* host_ = nullptr;
  std::string instance_name_;
};

// Bumped whenever the Component/Context/port layout changes incompatibly.
constexpr std::uint32_t kAbiVersion = 1;

// The C entry point's answer. abi_version stays the first field in every version.
struct ComponentEntry {
  std::uint32_t abi_version;
  const char* build_id;
  const char* type_name;
  Component* (*create)();
  void (*destroy)(Component*);
};

}  // namespace wysiwyf

#define WYSIWYF_COMPONENT_ENTRY_SYMBOL "wysiwyf_component_entry"

// Exports Class as the component type `type_name` (one per shared library).
#define WYSIWYF_COMPONENT(Class, type_name)                                                        \
  extern "C" __attribute__((visibility("default"))) const ::wysiwyf::ComponentEntry*              \
  wysiwyf_component_entry() {                                                                      \
    static const ::wysiwyf::ComponentEntry entry{                                                  \
        ::wysiwyf::kAbiVersion, WYSIWYF_BUILD_ID, type_name,                                       \
        []() -> ::wysiwyf::Component* { return new Class(); },                                     \
        [](::wysiwyf::Component* c) { delete c; }};                                                \
    return &entry;                                                                                 \
  }
