#pragma once
/// @file
/// Runs one component on its own, without DDS or an executor, for unit tests: load it by type,
/// configure it from a params map, feed its inputs, tick it at chosen times, read its outputs.
///
/// @code
///   wysiwyf::Harness h("wrench_script", "{keyframes: [0, 0,0,0, 0,0,0,  1, 0,0,10, 0,0,0]}");
///   auto out = h.watch<msg::WrenchStamped>("wrench");
///   h.activate();
///   h.tick(Time{500'000'000});
///   msg::WrenchStamped w; out.take(w);   // fz == 5
/// @endcode
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "wysiwyf/component.hpp"
#include "wysiwyf/component_description.hpp"
#include "wysiwyf/detail/topic_bus.hpp"
#include "wysiwyf/port.hpp"

namespace wysiwyf {

class Loader;  // the kernel's component loader (internal to the kernel)

/// Runs one component on its own, without DDS or an executor, for unit tests (see harness.hpp):
/// the component's ports are connected to ports the test holds (feed(), watch()), and what it
/// asks of the kernel (rejected samples, warnings, health, a stop) is kept for the test to read.
class Harness : private ComponentHost {
 public:
  /// Throws ConfigError when the params are wrong (the validator's messages), std::runtime_error
  /// (a LoadError) when the type cannot be loaded, saying where it looked. It searches the default
  /// component folders unless given the kernel's loader (tests inside this tree share one): a test
  /// finds the components built in its own build tree (lib/wysiwyf beside or above the test
  /// program) or an installed prefix's with no environment variable.
  Harness(const std::string& type, const std::string& params_yaml = "{}", double rate_hz = 1000,
          Loader* loader = nullptr);
  /// Deactivates the component if it is still active.
  ~Harness() override;
  Harness(const Harness&) = delete;
  Harness& operator=(const Harness&) = delete;

  /// An output that delivers to the component's input port `port`.
  template <class T>
  Output<T> feed(const std::string& port) {
    auto* channel = bus_.channel<T>(topic_of(port), "harness.feed");
    channel->add_writer(Qos::reliable());
    return Output<T>(channel);
  }
  /// An input receiving what the component writes on its output port `port`.
  template <class T>
  Input<T> watch(const std::string& port, int depth = 10000) {
    return Input<T>(bus_.channel<T>(topic_of(port), "harness.watch")->add_reader(Qos::reliable(depth)),
                    "watch " + port);
  }

  /// Calls the component's activate().
  void activate();
  /// Calls the component's tick(now): the test chooses the times.
  void tick(Time now);
  /// Calls the component's deactivate().
  void deactivate();
  /// The component under test.
  Component& component() { return *component_; }
  /// What the component type declares about itself (its parameters and ports).
  const ComponentDescription& description() const { return description_; }
  /// Set when the component asked the pipeline to stop.
  const std::string& stop_request() const { return stop_request_; }
  /// Samples the component rejected on input `port` (Component::reject).
  std::uint64_t rejected(const std::string& port) const;
  /// Warnings the component gave (Component::warn_once, Component::reject), each counted.
  std::uint64_t warnings() const { return warnings_; }
  /// The health the component last reported (report_health).
  Health health() const { return health_; }
  /// Why the component reported its last health.
  const std::string& health_reason() const { return health_reason_; }

 private:
  struct Kernel;  // the loader, the one-component pipeline and the library's deleter
  std::string topic_of(const std::string& port) const;  // the topic port `port` is mapped to
  void request_stop(const std::string& reason) override;
  void log(const std::string& message) override;
  void warn_once(const std::string& key, const std::string& message) override;
  void reject_sample(const std::string& port, const std::string& why) override;
  void report_health(Health health, const std::string& reason) override;

  ComponentDescription description_;
  detail::TopicBus bus_;
  std::unique_ptr<Kernel> kernel_;  // after bus_: the component goes before the channels it points into
  Component* component_ = nullptr;  // owned by kernel_
  bool active_ = false;
  std::string stop_request_;
  std::set<std::string> warned_;
  std::map<std::string, std::uint64_t> rejected_;
  std::uint64_t warnings_ = 0;
  Health health_ = Health::kOk;
  std::string health_reason_;
};

}  // namespace wysiwyf
