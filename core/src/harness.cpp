#include "wysiwyf/harness.hpp"

#include <iostream>

namespace wysiwyf {

Harness::Harness(const std::string& type, const std::string& params_yaml, double rate_hz, Loader* loader) {
  if (!loader) {
    own_loader_ = std::make_unique<Loader>();
    loader = own_loader_.get();
  }
  // A missing or broken library is reported as such (LoadError: where it looked, what it found),
  // not as an error in the harness's own pipeline text.
  loader->load(type);
  const std::string yaml = "wysiwyf: 1\nname: harness\nclock: {mode: real}\ncomponents:\n  dut:\n    type: " + type +
                           "\n    rate: " + std::to_string(rate_hz) + "\n    params: " + params_yaml + "\n";
  spec_ = load_pipeline_from_string(yaml, "<harness " + type + ">");
  ValidationResult v = validate_pipeline(spec_, *loader);
  if (!v.ok()) throw ConfigError(v.errors);
  description_ = v.described.at("dut");
  component_ = loader->create(type);
  component_->attach(this, "dut");
  Context ctx(Context::Mode::kRun, &spec_.components.front(), &bus_);
  component_->configure(ctx);
  if (!ctx.issues().empty()) throw ConfigError(ctx.issues());
}

Harness::~Harness() {
  if (active_) deactivate();
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
