// wysiwyf monitor: the component table of the running pipelines on a domain (the kernel's
// wysiwyf/diagnostics from every process) and the display mode, redrawn in place in a terminal.
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cctype>
#include <limits>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "bridge/sample_json.hpp"
#include "dds_session.hpp"
#include "raw_cdr_type.hpp"
#include "wysiwyf/runtime.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;
using json = nlohmann::json;

namespace {

// Keeps the last sample of each diagnostics instance and of the display mode, decoded.
class Latest final : public DataReaderListener {
 public:
  Latest(std::string type, bool keyed_by_instance) : type_(std::move(type)), keyed_(keyed_by_instance) {}
  void on_data_available(DataReader* reader) override {
    SampleInfo si;
    while (reader->take_next_sample(&sample_, &si) == ReturnCode_t::RETCODE_OK) {
      if (!si.valid_data) continue;
      std::lock_guard<std::mutex> lock(mutex_);
      auto j = decoder_.to_json(type_, sample_.bytes);
      if (!j) continue;
      const std::string key = keyed_ ? j->value("instance", "") : "";
      samples_[key] = {std::move(*j), Clock::now()};
    }
  }
  std::map<std::string, std::pair<json, Clock::time_point>> samples() {
    std::lock_guard<std::mutex> lock(mutex_);
    return samples_;
  }

 private:
  std::string type_;
  bool keyed_;
  std::mutex mutex_;
  RawCdr sample_;
  bridge::SampleDecoder decoder_;
  std::map<std::string, std::pair<json, Clock::time_point>> samples_;
};

std::string num(const json& j, const char* key, int precision) {
  if (!j.contains(key) || !j[key].is_number()) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << j[key].get<double>();
  return out.str();
}

std::string fit(std::string s, std::size_t width) {
  if (s.size() > width) s = s.substr(0, width > 1 ? width - 1 : 0) + "~";
  return s;
}

// "dropped at image: 3, pose: 1" from a row's dropped_by_port ("" when none dropped).
std::string dropped_by_port(const json& row) {
  if (!row.contains("dropped_by_port") || !row["dropped_by_port"].is_array() || row["dropped_by_port"].empty())
    return "";
  std::string out = "dropped at ";
  for (const auto& p : row["dropped_by_port"])
    out += (out.size() > 11 ? ", " : "") + p.value("port", "?") + ": " + p.value("count", json(0)).dump();
  return out;
}

// An enumerator as a word: STATE_ACTIVE -> active, MODE_SURFACE -> surface.
std::string label(const std::string& enumerator) {
  std::string out = enumerator.substr(enumerator.find('_') == std::string::npos ? 0 : enumerator.find('_') + 1);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

int terminal_width() {
  winsize w{};
  if (isatty(STDOUT_FILENO) && ioctl(STDOUT_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 40) return w.ws_col;
  return 160;
}

// The table, one row per component, ordered by process group then name.
std::string render(int domain, const std::map<std::string, std::pair<json, Clock::time_point>>& rows,
                   const std::map<std::string, std::pair<json, Clock::time_point>>& mode, int width) {
  std::ostringstream out;
  out << "wysiwyf monitor  domain " << domain << "  ";
  if (auto it = mode.find(""); it != mode.end()) {
    const auto& m = it->second.first;
    out << "display mode: " << label(m.value("mode", "?"));
    if (!m.value("reason", "").empty()) out << " (" << m.value("reason", "") << ")";
  } else {
    out << "display mode: -";
  }
  out << "\n";
  if (rows.empty()) {
    out << "(no component has reported yet: the kernel publishes wysiwyf/diagnostics once a second)\n";
    return out.str();
  }
  out << std::left << std::setw(16) << "component" << std::setw(18) << "type" << std::setw(10) << "process"
      << std::setw(9) << "state" << std::right << std::setw(15) << "rate Hz" << std::setw(9) << "p50 us" << std::setw(9)
      << "p99 us" << std::setw(9) << "overrun" << std::setw(9) << "dropped" << std::setw(9) << "rejected"
      << std::setw(7) << "warn"
      << "  problem\n";
  std::vector<std::pair<std::string, const json*>> ordered;
  std::map<std::string, double> age;
  const auto now = Clock::now();
  for (const auto& [instance, row] : rows) {
    ordered.push_back({row.first.value("process", "") + "/" + instance, &row.first});
    age[instance] = std::chrono::duration<double>(now - row.second).count();
  }
  std::sort(ordered.begin(), ordered.end());
  for (const auto& [order, j] : ordered) {
    const std::string instance = j->value("instance", "");
    std::string state = label(j->value("state", "?"));
    if (age[instance] > 3.0) state = "silent";  // its process stopped reporting
    std::string problem = j->value("last_error", "");
    if (problem.empty()) problem = j->value("last_warning", "");
    if (problem.empty()) problem = dropped_by_port(*j);
    const std::string rate = num(*j, "tick_rate_hz", 1) + "/" + num(*j, "rate_hz", 0);
    out << std::left << std::setw(16) << fit(instance, 15) << std::setw(18) << fit(j->value("type", ""), 17)
        << std::setw(10) << fit(j->value("process", ""), 9) << std::setw(9) << state << std::right << std::setw(15)
        << rate << std::setw(9) << num(*j, "tick_time_p50_us", 1) << std::setw(9) << num(*j, "tick_time_p99_us", 1)
        << std::setw(9) << num(*j, "overruns", 0) << std::setw(9) << num(*j, "dropped_samples", 0) << std::setw(9)
        << num(*j, "rejected_samples", 0) << std::setw(7) << num(*j, "warnings", 0) << "  "
        << fit(problem, static_cast<std::size_t>(std::max(10, width - 117))) << "\n";
  }
  return out.str();
}

}  // namespace

int cmd_monitor(Args args) {
  Session s;
  open(args, s);
  const double interval = number_option(args, "--interval", 0.5, 0.001, 3600, "a number of seconds, 0.001 to 3600");
  const double duration = number_option(args, "--duration", 0, 0, std::numeric_limits<double>::infinity(),
                                        "a number of seconds (0: until Ctrl-C)");
  const bool once = args.flag("--once");
  const std::string diagnostics_topic = "wysiwyf/diagnostics";
  const std::string mode_topic = args.value("--mode-topic").value_or("display/mode");
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  install_stop_signal_handlers();
  const bool tty = isatty(STDOUT_FILENO);

  Subscriber* subscriber = s.participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  Latest diagnostics("wysiwyf::kernel_msgs::Diagnostics", true), mode("wysiwyf::msg::DisplayMode", false);
  bool reading_diagnostics = false, reading_mode = false;
  const auto start = Clock::now();
  auto next_draw = start;
  if (tty && !once) std::cout << "\x1b[2J\x1b[?25l";  // a clear screen, no cursor while redrawing
  while (!stop_signal_received() && (duration == 0 || Clock::now() - start < std::chrono::duration<double>(duration))) {
    const auto topics = s.discovery.topics();
    for (auto [topic, latest, reading] : {std::tuple{&diagnostics_topic, &diagnostics, &reading_diagnostics},
                                          std::tuple{&mode_topic, &mode, &reading_mode}}) {
      auto it = topics.find(*topic);
      if (*reading || it == topics.end() || it->second.writers.empty()) continue;
      *reading =
          open_raw_reader(s, subscriber, *topic, it->second, 64, latest, StatusMask::data_available()) != nullptr;
    }
    if (Clock::now() >= next_draw) {
      const auto rows = diagnostics.samples();
      if (once) {
        if (!rows.empty() || Clock::now() - start > std::chrono::seconds(10)) {
          std::this_thread::sleep_for(std::chrono::milliseconds(2200));  // a full window from every process
          std::cout << render(s.domain, diagnostics.samples(), mode.samples(), terminal_width()) << std::flush;
          return rows.empty() ? 1 : 0;
        }
      } else {
        const std::string table = render(s.domain, rows, mode.samples(), terminal_width());
        // In place on a terminal (home, the table, clear the rest); one table after another otherwise.
        std::cout << (tty ? "\x1b[H" : "") << table << (tty ? "\x1b[J" : "\n") << std::flush;
      }
      next_draw += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(interval));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (tty && !once) std::cout << "\x1b[?25h";
  s.participant->delete_contained_entities();
  return 0;
}

}  // namespace wysiwyf::cli
