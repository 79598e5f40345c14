#include "wysiwyf/harness.hpp"

#include <iostream>

#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/validator.hpp"

namespace wysiwyf {

struct Harness::Kernel {
  std::unique_ptr<Loader> own_loader;
  PipelineSpec spec;
  ComponentPtr component;  // destroyed by its library's own function, before the loader
};

Harness::Harness(const std::string& type, const std::string& params_yaml, double rate_hz, Loader* loader)
    : kernel_(std::make_unique<Kernel>()) {
  if (!loader) {
    kernel_->own_loader = std::make_unique<Loader>();
    loader = kernel_->own_loader.get();
  }
  PipelineSpec& spec = kernel_->spec;
  // A missing or broken library is reported as such (LoadError: where it looked, what it found),
  // not as an error in the harness's own pipeline text.
  loader->load(type);
  // (insecure: the test writes the component's one-writer inputs itself, in this process; the
  // harness has no DDS. Last, so that the parameters' line numbers are what they always were.)
  const std::string yaml = "wysiwyf: 1\nname: harness\nclock: {mode: real}\ncomponents:\n  dut:\n    type: " + type +
                           "\n    rate: " + std::to_string(rate_hz) + "\n    params: " + params_yaml +
                           "\ninsecure: true\n";
  spec = load_pipeline_from_string(yaml, "<harness " + type + ">");
  ValidationResult v = validate_pipeline(spec, *loader);
  if (!v.ok()) throw ConfigError(v.errors);
  description_ = v.described.at("dut");
  kernel_->component = loader->create(type);
  component_ = kernel_->component.get();
  component_->attach(this, "dut");
  Context ctx(Context::Mode::kRun, &spec.components.front(), &bus_);
  component_->configure(ctx);
  if (!ctx.issues().empty()) throw ConfigError(ctx.issues());
}

Harness::~Harness() {
  if (active_) deactivate();
}

std::string Harness::topic_of(const std::string& port) const {
  return kernel_->spec.components.front().topic_for(port);
}

void Harness::activate() {
  component_->activate();
  active_ = true;
}

void Harness::tick(Time now) { component_->tick(now); }

void Harness::deactivate() {
  active_ = false;
  component_->deactivate();
}

void Harness::request_stop(const std::string& reason) { stop_request_ = reason; }

void Harness::log(const std::string& message) { std::cerr << "[dut] " << message << "\n"; }

void Harness::warn_once(const std::string& key, const std::string& message) {
  ++warnings_;
  if (warned_.insert(key).second) log("warning: " + message);
}

void Harness::report_health(Health health, const std::string& reason) {
  health_ = health;
  health_reason_ = reason;
}

void Harness::reject_sample(const std::string& port, const std::string& why) {
  ++rejected_[port];
  warn_once("reject " + port + ": " + why, "input '" + port + "': rejected a sample: " + why);
}

std::uint64_t Harness::rejected(const std::string& port) const {
  const auto it = rejected_.find(port);
  return it == rejected_.end() ? 0 : it->second;
}

}  // namespace wysiwyf
