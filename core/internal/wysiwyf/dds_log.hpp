#pragma once
// Fast DDS's own log, said once per kind of message: a sample it refuses (over its type's bound,
// say) is logged by Fast DDS once per sample, 140 lines in 0.3 s from one bad writer. Each message
// of a source line is said the first time, then counted, with the count said at 10, 100, 1000...
#include <fastdds/dds/log/Log.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>

namespace wysiwyf::dds {

class CountingLogConsumer final : public eprosima::fastdds::dds::LogConsumer {
 public:
  explicit CountingLogConsumer(std::function<void(const std::string&)> write) : write_(std::move(write)) {}
  void Consume(const eprosima::fastdds::dds::Log::Entry& entry) override;

 private:
  std::mutex mutex_;
  std::map<std::string, std::uint64_t> seen_;  // by category and source line
  std::function<void(const std::string&)> write_;
};

// Routes this process's Fast DDS log to standard error through a CountingLogConsumer (once; the
// bridge and the tools call it before they create a participant).
void route_fast_dds_log();

}  // namespace wysiwyf::dds
