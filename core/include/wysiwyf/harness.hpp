#pragma once
// Runs one component on its own, without DDS or an executor, for unit tests: load it by type,
// configure it from a params map, feed its inputs, tick it at chosen times, read its outputs.
//
//   wysiwyf::Harness h("wrench_script", "{keyframes: [0, 0,0,0, 0,0,0,  1, 0,0,10, 0,0,0]}");
//   auto out = h.watch<msg::WrenchStamped>("wrench");
//   h.activate();
//   h.tick(Time{500'000'000});
//   msg::WrenchStamped w; out.take(w);   // fz == 5
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/validator.hpp"

namespace wysiwyf {

class Harness : private ComponentHost {
 public:
  // Throws ConfigError when the params are wrong (the validator's messages), LoadError when the
  // type cannot be loaded (saying where it looked). The loader searches
  // Loader::default_search_dirs() unless given one: a test finds the components built in its own
  // build tree (lib/wysiwyf beside or above the test program) with no environment variable.
  Harness(const std::string& type, const std::string& params_yaml = "{}", double rate_hz = 1000,
          Loader* loader = nullptr);
  ~Harness() override;
  Harness(const Harness&) = delete;
  Harness& operator=(const Harness&) = delete;

  // An output that delivers to the component's input port `port`.
  template <class T>
  Output<T> feed(const std::string& port) {
    auto* channel = bus_.channel<T>(spec_.components.front().topic_for(port), "harness.feed");
    channel->add_writer(Qos::reliable());
    return Output<T>(channel);
  }
  // An input receiving what the component writes on its output port `port`.
  template <class T>
  Input<T> watch(const std::string& port, int depth = 10000) {
    return Input<T>(
        bus_.channel<T>(spec_.components.front().topic_for(port), "harness.watch")->add_reader(Qos::reliable(depth)),
        "watch " + port);
  }

  void activate();
  void tick(Time now);
  void deactivate();
  Component& component() { return *component_; }
  const ComponentDescription& description() const { return description_; }
  // Set when the component asked the pipeline to stop.
  const std::string& stop_request() const { return stop_request_; }
  // Samples the component rejected on input `port` (Component::reject), and warnings it gave.
  std::uint64_t rejected(const std::string& port) const;
  std::uint64_t warnings() const { return warnings_; }
  // The health the component last reported (report_health), and why.
  Health health() const { return health_; }
  const std::string& health_reason() const { return health_reason_; }

 private:
  void request_stop(const std::string& reason) override;
  void log(const std::string& message) override;
  void warn_once(const std::string& key, const std::string& message) override;
  void reject_sample(const std::string& port, const std::string& why) override;
  void report_health(Health health, const std::string& reason) override;

  std::unique_ptr<Loader> own_loader_;
  PipelineSpec spec_;
  ComponentDescription description_;
  detail::TopicBus bus_;
  ComponentPtr component_;
  bool active_ = false;
  std::string stop_request_;
  std::set<std::string> warned_;
  std::map<std::string, std::uint64_t> rejected_;
  std::uint64_t warnings_ = 0;
  Health health_ = Health::kOk;
  std::string health_reason_;
};

}  // namespace wysiwyf
