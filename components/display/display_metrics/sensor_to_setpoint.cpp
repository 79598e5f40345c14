#include "sensor_to_setpoint.hpp"

namespace wysiwyf::display {

namespace {
bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}
constexpr std::size_t kMaxPending = 100'000;  // samples no setpoint answers (another mode) are dropped
}  // namespace

std::string SensorToSetpoint::sensor_of(const std::string& source) {
  if (ends_with(source, "admittance")) return "wrench";
  if (ends_with(source, "surface")) return "hand";
  return source;
}

void SensorToSetpoint::sample(const std::string& sensor, std::int64_t t_ns) {
  auto& s = streams_[sensor].samples;
  if (!s.empty() && t_ns <= s.back()) return;  // not newer
  s.push_back(t_ns);
  if (s.size() > kMaxPending) s.pop_front();
}

void SensorToSetpoint::setpoint(const std::string& source, std::int64_t stamp_ns, std::int64_t sensed_ns) {
  if (sensed_ns <= 0) {
    run_.clear();
    return;
  }
  const std::string sensor = sensor_of(source);
  Stream& s = streams_[sensor];
  const bool continuing = run_ == source && s.answered > 0;
  run_ = source;
  if (sensed_ns <= s.answered) return;  // answered already
  auto& ms = by_sensor_[sensor];
  std::size_t counted = 0;
  while (!s.samples.empty() && s.samples.front() <= sensed_ns) {
    // In a run, every sample since the last answered one waited for this setpoint.
    if (continuing && s.samples.front() > s.answered)
      ms.add(static_cast<double>(stamp_ns - s.samples.front()) * 1e-6, stamp_ns), ++counted;
    s.samples.pop_front();
  }
  if (!counted) ms.add(static_cast<double>(stamp_ns - sensed_ns) * 1e-6, stamp_ns);
  s.answered = sensed_ns;
}

}  // namespace wysiwyf::display
