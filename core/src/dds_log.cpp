// Fast DDS's log, once per kind of message, then counted (CountingLogConsumer).
#include "wysiwyf/dds_log.hpp"

#include <iostream>

namespace wysiwyf::dds {

using eprosima::fastdds::dds::Log;

void CountingLogConsumer::Consume(const Log::Entry& entry) {
  const char* kind = entry.kind == Log::Kind::Error ? "ERROR" : entry.kind == Log::Kind::Warning ? "warning" : "info";
  const std::string category = entry.context.category ? entry.context.category : "";
  const std::string key = category + "@" + (entry.context.filename ? entry.context.filename : entry.message) + ":" +
                          std::to_string(entry.context.line);
  std::uint64_t count = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    count = ++seen_[key];
  }
  std::uint64_t said_at = 1;
  while (said_at < count) said_at *= 10;
  if (said_at != count) return;  // (said at 1, 10, 100, ...)
  write_("[fastdds] " + std::string(kind) + " " + category + ": " +
         (count == 1 ? "" : std::to_string(count) + " times so far (said at 1, 10, 100, ...): ") + entry.message);
}

void route_fast_dds_log() {
  static std::once_flag once;
  std::call_once(once, [] {
    Log::ClearConsumers();
    Log::RegisterConsumer(
        std::make_unique<CountingLogConsumer>([](const std::string& line) { std::cerr << line << "\n"; }));
  });
}

}  // namespace wysiwyf::dds
